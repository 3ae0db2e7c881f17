// Force laws: a wire never pushes, NaN never leaks, parameters are checked, and the built-in laws match
// their formulas (evaluated here independently).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "sinew/core/builtin_force_laws.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/force_law_registry.hpp"

namespace sinew {
namespace {

std::shared_ptr<const ForceLaw> make(const std::string& type, std::map<std::string, std::vector<double>> parameters) {
    return ForceLawRegistry::global().create(type, ForceLawParameters(std::move(parameters)));
}

TEST(ForceLaws, SpringDamperNeverPushesAndMatchesItsFormula) {
    const auto law = make("spring_damper", {{"stiffness", {800}}, {"damping", {30}}, {"rest_length", {0.25}}});
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> length(0.0, 0.5), speed(-20, 20);
    for (int i = 0; i < 100000; ++i) {
        const WireState s{length(rng), speed(rng), 0.0};
        const double tension = law->calcTension(s);
        ASSERT_GE(tension, 0.0) << "pushed at l=" << s.length << " v=" << s.speed;
        const double expected = s.length > 0.25 ? std::max(0.0, 800 * (s.length - 0.25) + 30 * s.speed) : 0.0;
        ASSERT_NEAR(tension, expected, 1e-9);
    }
}

TEST(ForceLaws, SpringDamperPotentialEnergyIsTheIntegralOfTension) {
    const auto law = make("spring_damper", {{"stiffness", {1200}}, {"rest_length", {0.3}}});
    for (double l : {0.1, 0.29, 0.31, 0.4, 0.7}) {
        const double h = 1e-6;
        const double dEdl = (law->calcPotentialEnergy(l + h) - law->calcPotentialEnergy(l - h)) / (2 * h);
        EXPECT_NEAR(dEdl, law->calcTension({l, 0, 0}), 1e-5) << "l=" << l;
    }
}

TEST(ForceLaws, PrescribedTensionInterpolatesAndHoldsEnds) {
    const auto series = make("prescribed_tension", {{"times", {0, 1, 3}}, {"tensions", {10, 30, 0}}});
    EXPECT_DOUBLE_EQ(series->calcTension({0, 0, -1}), 10);
    EXPECT_DOUBLE_EQ(series->calcTension({0, 0, 0.5}), 20);
    EXPECT_DOUBLE_EQ(series->calcTension({0, 0, 2}), 15);
    EXPECT_DOUBLE_EQ(series->calcTension({0, 0, 9}), 0);
    const auto constant = make("prescribed_tension", {{"tension", {42}}});
    EXPECT_DOUBLE_EQ(constant->calcTension({0.1, -3, 7}), 42);
}

TEST(ForceLaws, RejectsBadParameters) {
    auto expectError = [](const std::string& type, std::map<std::string, std::vector<double>> p, const std::string& text) {
        try {
            make(type, std::move(p));
            ADD_FAILURE() << "no error; expected one mentioning '" << text << "'";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    expectError("spring_damper", {{"stiffness", {-1}}, {"rest_length", {0.2}}}, "stiffness");
    expectError("spring_damper", {{"stiffness", {1}}, {"rest_length", {0}}}, "rest_length");
    expectError("spring_damper", {{"stiffness", {1}}}, "missing parameter 'rest_length'");
    expectError("spring_damper", {{"stiffness", {1}}, {"rest_length", {1}}, {"stifness", {2}}}, "'stifness'");
    expectError("prescribed_tension", {{"times", {0, 0}}, {"tensions", {1, 2}}}, "strictly increasing");
    expectError("prescribed_tension", {{"times", {0, 1}}, {"tensions", {1}}}, "same");
    expectError("prescribed_tension", {{"tension", {-5}}}, "tensions");
    expectError("prescribed_tension", {{"tension", {1}}, {"times", {0}}}, "either");
    expectError("no_such_law", {}, "unknown force law type 'no_such_law'");
}

// A user law that returns negative or NaN values: the wrapper clamps the first and reports the second.
class Misbehaving final : public ForceLaw {
protected:
    double doCalcTension(const WireState& state) const override {
        return state.speed > 0 ? std::numeric_limits<double>::quiet_NaN() : -state.length;
    }
};

TEST(ForceLaws, WrapperClampsPushingLawsAndRejectsNaN) {
    const Misbehaving law;
    EXPECT_EQ(law.calcTension({0.3, -1, 0}), 0.0);
    EXPECT_THROW(law.calcTension({0.3, 1, 0}), Error);
}

TEST(ForceLawRegistry, AddsUserLawsAndRefusesDuplicates) {
    ForceLawRegistry& registry = ForceLawRegistry::global();
    registry.add("test_constant_7", [](const ForceLawParameters&) {
        return std::make_shared<PrescribedTension>(std::vector<double>{0}, std::vector<double>{7});
    });
    EXPECT_TRUE(registry.contains("test_constant_7"));
    EXPECT_DOUBLE_EQ(registry.create("test_constant_7", {})->calcTension({}), 7);
    EXPECT_THROW(registry.add("spring_damper", nullptr), Error);
}

}  // namespace
}  // namespace sinew
