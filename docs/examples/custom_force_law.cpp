// How a researcher adds a wire force law to sinew without touching sinew's code (docs/force-laws.md).
//
// The law: a passive muscle (parallel elastic element) whose tension grows exponentially with strain, as in
// the passive force-length curves of Hill-type muscle models (e.g. Thelen 2003), plus linear damping:
//
//   strain  e = (l - l0) / l0
//   tension T = f0 * (exp(k * e) - 1) + d * dl/dt   while l > l0, else 0 (slack)
//
//   scale_force  f0  N       > 0   tension scale; T = f0 * (e^k - 1) at 100% strain
//   shape        k   -       > 0   stiffening rate; the stiffness at rest length is f0 * k / l0
//   rest_length  l0  m       > 0   slack length
//   damping      d   N*s/m   >= 0  optional, default 0
//
// The elastic part is conservative, with potential energy (the integral of the elastic tension from l0 to l)
//
//   V(l) = f0 * (l0 / k * (exp(k * e) - 1) - (l - l0))   for l > l0, else 0.
//
// The program registers the law under the name "exponential_muscle", loads a two-link pendulum whose one
// wire uses it, and checks that sinew's core (calcWireTensions) and its Simbody plugin (WireForce) give the
// tension worked out here by hand, at rest and with the elbow moving. It exits non-zero, saying why, if not.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/force_law.hpp"
#include "sinew/core/force_law_registry.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_model.hpp"

namespace {

// --- 1. The law: derive from sinew::ForceLaw and implement the protected virtuals. -----------------------
class ExponentialMuscle final : public sinew::ForceLaw {
public:
    ExponentialMuscle(double scaleForce, double shape, double restLength, double damping)
        : scaleForce_(scaleForce), shape_(shape), restLength_(restLength), damping_(damping) {
        // Bad parameters throw sinew::Error; the model reader prefixes the wire's file:line and name.
        if (!(scaleForce > 0) || !std::isfinite(scaleForce))
            throw sinew::Error("parameter 'scale_force' must be a finite number > 0 (N)");
        if (!(shape > 0) || !std::isfinite(shape))
            throw sinew::Error("parameter 'shape' must be a finite number > 0");
        if (!(restLength > 0) || !std::isfinite(restLength))
            throw sinew::Error("parameter 'rest_length' must be a finite number > 0 (m)");
        if (!(damping >= 0) || !std::isfinite(damping))
            throw sinew::Error("parameter 'damping' must be a finite number >= 0 (N*s/m)");
    }

    // --- 2. The factory: reads every parameter it understands. A parameter it does not read (a typo in the
    // model file) makes ForceLawRegistry::create fail, so nothing is silently ignored.
    static std::shared_ptr<const sinew::ForceLaw> create(const sinew::ForceLawParameters& parameters) {
        return std::make_shared<ExponentialMuscle>(parameters.getScalar("scale_force"), parameters.getScalar("shape"),
                                                   parameters.getScalar("rest_length"),
                                                   parameters.getScalarOr("damping", 0.0));
    }

protected:
    // May return a negative number (a taut wire shortening fast): ForceLaw::calcTension clamps it to 0, since
    // a wire cannot push, and rejects NaN or inf.
    double doCalcTension(const sinew::WireState& state) const override {
        const double stretch = state.length - restLength_;
        if (stretch <= 0) return 0;  // slack
        return scaleForce_ * std::expm1(shape_ * stretch / restLength_) + damping_ * state.speed;
    }

    // The elastic part only: damping stores no energy. Used by energy reports (calcWirePotentialEnergy,
    // Simbody's potential energy, the simulate command's energy drift).
    double doCalcPotentialEnergy(double length) const override {
        const double stretch = length - restLength_;
        if (stretch <= 0) return 0;
        return scaleForce_ * (restLength_ / shape_ * std::expm1(shape_ * stretch / restLength_) - stretch);
    }

private:
    double scaleForce_;  // N
    double shape_;       // dimensionless
    double restLength_;  // m
    double damping_;     // N*s/m
};

// --- 3. A model that names the law. A two-link pendulum in the x-y plane, both pins about z: the upper link
// hangs from the ground origin, the lower one from the upper's tip at y = -0.5 m, flexed 0.3 rad. The wire
// runs down the upper link's +x side through a via-point to the lower link.
const char* const kModelText = R"(sinew_model: 1
name: two_link_pendulum
gravity: [0, -9.80665, 0]
links:
  - {name: upper, mass: 2.0, com: [0, -0.25, 0], inertia: [0.042, 0.002, 0.042, 0, 0, 0]}
  - {name: lower, mass: 1.5, com: [0, -0.25, 0], inertia: [0.032, 0.0015, 0.032, 0, 0, 0]}
joints:
  - {name: shoulder, type: pin, parent: ground, child: upper, axis: [0, 0, 1]}
  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.5, 0], axis: [0, 0, 1],
     initial_angle: 0.3}
wires:
  - name: flexor
    kind: muscle
    points:
      - {link: upper, at: [0.05, -0.1, 0]}
      - {link: upper, at: [0.05, -0.4, 0]}
      - {link: lower, at: [0.05, -0.2, 0]}
    force_law: {type: exponential_muscle, scale_force: 100, shape: 5, rest_length: 0.52, damping: 2}
)";

// The law once more, written out independently of the class, for the check.
double calcTensionByHand(double length, double speed) {
    const double f0 = 100, k = 5, l0 = 0.52, d = 2;
    if (length <= l0) return 0;
    return std::max(0.0, f0 * (std::exp(k * (length - l0) / l0) - 1) + d * speed);
}

int failures = 0;

void check(const char* what, double got, double expected, double tolerance = 1e-10) {
    const bool ok = std::abs(got - expected) <= tolerance * (1 + std::abs(expected));
    std::printf("%-46s %.12g (expected %.12g)%s\n", what, got, expected, ok ? "" : "  <-- MISMATCH");
    if (!ok) ++failures;
}

}  // namespace

int main() {
    try {
        // --- 4. Register before any model naming the law is read. (In a program's own translation unit a
        // static `sinew::ForceLawRegistration reg{"exponential_muscle", &ExponentialMuscle::create};`
        // does the same at start-up.)
        sinew::ForceLawRegistry::global().add("exponential_muscle", &ExponentialMuscle::create);

        const sinew::Model model = sinew::readModelText(kModelText, "two_link_pendulum.yaml");

        // The geometry by hand, at the default pose (shoulder 0, so the upper link's frame is ground's).
        const double theta = 0.3, omega = 1.5;  // elbow angle (rad) and, for the moving case, rate (rad/s)
        const double c = std::cos(theta), s = std::sin(theta);
        const double r_x = 0.05 * c + 0.2 * s, r_y = 0.05 * s - 0.2 * c;  // insertion from the elbow, in G
        const double dx = r_x - 0.05, dy = (-0.5 + r_y) - (-0.4);        // via-point to insertion, in G
        const double lastSegment = std::hypot(dx, dy);
        const double lengthByHand = 0.3 + lastSegment;  // 0.3 m from origin to via-point on the upper link
        // Insertion velocity omega z x r, projected on the last segment: the only segment that changes length.
        const double speedByHand = (dx * (-omega * r_y) + dy * (omega * r_x)) / lastSegment;

        // --- 5a. sinew's core: kinematics, wire paths, tensions.
        sinew::Data data(model);
        const Eigen::VectorXd q = model.getDefaultQ();
        Eigen::VectorXd u = Eigen::VectorXd::Zero(model.getNumU());
        Eigen::VectorXd tensions(model.getNumWires());
        sinew::calcPositionKinematics(model, data, q);
        sinew::calcVelocityKinematics(model, data, u);
        sinew::calcWirePaths(model, data);
        sinew::calcWireSpeeds(model, data);
        sinew::calcWireTensions(model, data, 0.0, tensions);
        check("core: wire length at rest (m)", data.wireLength[0], lengthByHand);
        check("core: tension at rest (N)", tensions[0], calcTensionByHand(lengthByHand, 0));

        // --- 5b. The Simbody plugin: the same law inside a SimTK::Force::Custom, on Simbody's kinematics.
        const sinew::SimbodyModel simbody(model);
        const SimTK::State rest = simbody.makeDefaultState();
        check("simbody: wire length at rest (m)", simbody.getWireForce(0).calcLength(rest), lengthByHand);
        check("simbody: tension at rest (N)", simbody.getWireForce(0).calcTension(rest),
              calcTensionByHand(lengthByHand, 0));

        // The elbow flexing at omega: the wire shortens, so the damping term lowers the tension.
        u[model.getJoint(model.findLinkIndex("lower")).uStart] = omega;
        sinew::calcVelocityKinematics(model, data, u);
        sinew::calcWireSpeeds(model, data);
        sinew::calcWireTensions(model, data, 0.0, tensions);
        const double tensionMoving = calcTensionByHand(lengthByHand, speedByHand);
        check("core: lengthening speed, elbow moving (m/s)", data.wireSpeed[0], speedByHand);
        check("core: tension, elbow moving (N)", tensions[0], tensionMoving);
        const SimTK::State moving = simbody.makeState(q, u);
        check("simbody: tension, elbow moving (N)", simbody.getWireForce(0).calcTension(moving), tensionMoving);

        // The potential energy is the integral of the elastic tension: its derivative must give the tension.
        const sinew::ForceLaw& law = *model.getWire(0).law;
        const double h = 1e-6;
        check("dV/dl by central difference (N)",
              (law.calcPotentialEnergy(lengthByHand + h) - law.calcPotentialEnergy(lengthByHand - h)) / (2 * h),
              calcTensionByHand(lengthByHand, 0), 1e-7);
        check("simbody: wire potential energy (J)", simbody.getWireForce(0).calcPotentialEnergy(rest),
              sinew::calcWirePotentialEnergy(model, data));

        // A misspelt parameter is an error naming the file, line, wire and parameter.
        std::string typo = kModelText;
        typo.replace(typo.find("damping: 2"), 10, "dampng: 2");
        try {
            sinew::readModelText(typo, "typo.yaml");
            std::printf("a misspelt force-law parameter was accepted\n");
            ++failures;
        } catch (const sinew::ModelError& e) {
            std::printf("misspelt parameter rejected: %s\n", e.what());
            if (std::string(e.what()).find("'dampng'") == std::string::npos) {
                std::printf("  <-- the message does not name the parameter\n");
                ++failures;
            }
        }
    } catch (const std::exception& e) {
        std::printf("error: %s\n", e.what());
        return 1;
    }
    if (failures != 0) {
        std::printf("%d check(s) failed: the law as registered does not give the tension worked out by hand\n",
                    failures);
        return 1;
    }
    std::printf("all checks passed\n");
    return 0;
}
