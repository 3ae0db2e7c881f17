// A user's program: load a model, embed it in a Simbody system, and check that Simbody's wire speeds are
// sinew's J u at the model's initial pose with random speeds.
#include <cstdio>
#include <random>
#include <sinew/core/data.hpp>
#include <sinew/core/kinematics.hpp>
#include <sinew/core/wire_jacobian.hpp>
#include <sinew/core/wire_path.hpp>
#include <sinew/io/model_file.hpp>
#include <sinew/plugin/simbody_model.hpp>

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    const sinew::Model model = sinew::readModelFile(argv[1]);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> speed(-1.0, 1.0);
    const Eigen::VectorXd q = model.getDefaultQ();
    Eigen::VectorXd u(model.getNumU());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = speed(rng);
    sinew::Data data(model);
    sinew::calcPositionKinematics(model, data, q);
    sinew::calcWirePaths(model, data);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    sinew::calcWireJacobian(model, data, J);
    const Eigen::VectorXd speeds = J * u;

    const sinew::SimbodyModel simbody(model);
    const SimTK::State state = simbody.makeState(q, u);
    double worst = 0;
    for (int w = 0; w < model.getNumWires(); ++w)
        worst = std::max(worst, std::abs(simbody.getWireForce(w).calcLengtheningSpeed(state) - speeds[w]));
    std::printf("consumer: %d wires, max |J u - Simbody speed| = %.3g m/s\n", model.getNumWires(), worst);
    return worst < 1e-10 ? 0 : 1;
}
