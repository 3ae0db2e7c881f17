// Measured external loads on a model: the loads' curves fitted beforehand (as the inverse dynamics tool
// fits them beside the model's reading) give the same loads and the same first error as fitting them
// with the model at hand.
#include <gtest/gtest.h>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "support/error_assertions.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

// Two forces on `body`, their data sampled at 100 Hz; `spike` (if not 0) puts that value in the second
// force's y component at row 5.
ExternalLoads makeLoads(const std::string& firstBody, const std::string& body, double spike) {
    ExternalLoads loads;
    loads.file = "loads.xml";
    loads.dataFile = "loads.mot";
    loads.data.name = "plates";
    loads.data.columns = {"a_vx", "a_vy", "a_vz", "a_px", "a_py", "a_pz", "b_vx", "b_vy", "b_vz"};
    for (int r = 0; r <= 20; ++r) {
        const double t = 0.01 * r;
        loads.data.times.push_back(t);
        loads.data.rows.push_back({10 * std::sin(5 * t), 700 + 50 * t, -3.0, 0.1 * t, 0.0, 0.05, 2.0, 100 * t, 1.0});
    }
    if (spike != 0) loads.data.rows[5][7] = spike;
    ExternalForce first, second;
    first.name = "a";
    first.appliedToBody = firstBody;
    first.forceColumns = {0, 1, 2};
    first.pointColumns = {3, 4, 5};
    first.where = "loads.xml:3";
    second.name = "b";
    second.appliedToBody = body;
    second.forceColumns = {6, 7, 8};
    second.where = "loads.xml:9";
    loads.forces = {first, second};
    return loads;
}

TEST(MeasuredLoads, CurvesFittedBeforehandGiveTheSameLinkForces) {
    const Model model = test::loadArm26().model;
    const std::string body = model.getLinks().back().name;
    const ExternalLoads loads = makeLoads(body, body, 0);
    const MeasuredLoads here(model, loads), beforehand(model, loads, ExternalLoadCurves(loads));
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    for (double t : {0.0, 0.033, 0.1, 0.2}) {
        std::vector<SpatialVector> a(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero()), b = a;
        here.addLinkForces(data, t, a);
        beforehand.addLinkForces(data, t, b);
        for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "link " << i << " t " << t;
        EXPECT_GT(a.back().norm(), 100);
    }
}

// The first force names a body the model lacks and the second has a value beyond the bound: the body's
// error comes first, force by force, whether the curves were fitted with the model or before it.
TEST(MeasuredLoads, ErrorsComeForceByForceEitherWay) {
    const Model model = test::loadArm26().model;
    const std::string body = model.getLinks().back().name;
    const ExternalLoads bad = makeLoads("no_such_body", body, 2e7);
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { MeasuredLoads(model, bad); }, "loads.xml:3", {"'no_such_body'"}, "fitted here"));
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { MeasuredLoads(model, bad, ExternalLoadCurves(bad)); }, "loads.xml:3",
                                                {"'no_such_body'"}, "fitted before"));
    const ExternalLoads spiked = makeLoads(body, body, 2e7);
    for (bool before : {false, true})
        EXPECT_TRUE(test::throwsErrorAt([&] { before ? MeasuredLoads(model, spiked, ExternalLoadCurves(spiked)) : MeasuredLoads(model, spiked); },
                                        "storage table 'plates' row 5", {"'b_vy'", "external load"},
                                        before ? "fitted before" : "fitted here"));
    const ExternalLoads other = makeLoads(body, body, 0);
    ExternalLoads fewer = other;
    fewer.forces.pop_back();
    EXPECT_TRUE(test::throwsErrorAt([&] { MeasuredLoads(model, fewer, ExternalLoadCurves(other)); }, "loads.xml",
                                    {"fitted to other external loads"}, "curves of two forces for one"));
}

}  // namespace
}  // namespace sinew
