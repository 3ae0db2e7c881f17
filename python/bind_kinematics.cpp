// Kinematics of the links and wires (core/kinematics.hpp, core/wire_path.hpp, core/wire_jacobian.hpp). Each
// call fills a Data of its own, so calls are independent (and safe from several threads).
#include "bindings.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew::python {
namespace {

// Data after calcPositionKinematics and calcWirePaths at q.
Data calcWireGeometry(const Model& model, const Eigen::VectorXd& q) {
    checkSize(model, q, model.getNumQ(), "q");
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    return data;
}

}  // namespace

void bindKinematics(py::module_& m) {
    m.def(
        "calc_link_poses",
        [](const Model& model, const Eigen::VectorXd& q) {
            checkSize(model, q, model.getNumQ(), "q");
            Data data(model);
            calcPositionKinematics(model, data, q);
            const auto n = static_cast<py::ssize_t>(model.getNumLinks());
            py::array_t<double> R_GB({n, py::ssize_t(3), py::ssize_t(3)}), p_GB({n, py::ssize_t(3)});
            auto R = R_GB.mutable_unchecked<3>();
            auto p = p_GB.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < n; ++i)
                for (int r = 0; r < 3; ++r) {
                    p(i, r) = data.p_GB[static_cast<std::size_t>(i)][r];
                    for (int c = 0; c < 3; ++c) R(i, r, c) = data.R_GB[static_cast<std::size_t>(i)](r, c);
                }
            return py::make_tuple(R_GB, p_GB);
        },
        py::arg("model"), py::arg("q"),
        "(R_GB, p_GB) at q: each link frame's orientation (numLinks x 3 x 3) and origin (numLinks x 3, m) in ground.");
    m.def(
        "calc_wire_lengths",
        [](const Model& model, const Eigen::VectorXd& q) { return Eigen::VectorXd(calcWireGeometry(model, q).wireLength); },
        py::arg("model"), py::arg("q"), "Wire lengths (numWires, m) at q.");
    m.def(
        "calc_wire_speeds",
        [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u) {
            Data data = calcWireGeometry(model, q);
            checkSize(model, u, model.getNumU(), "u");
            calcVelocityKinematics(model, data, u);
            calcWireSpeeds(model, data);
            return Eigen::VectorXd(data.wireSpeed);
        },
        py::arg("model"), py::arg("q"), py::arg("u"), "Wire lengthening speeds (numWires, m/s) at (q, u).");
    m.def(
        "calc_wire_jacobian",
        [](const Model& model, const Eigen::VectorXd& q) {
            Data data = calcWireGeometry(model, q);
            Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
            calcWireJacobian(model, data, J);
            return J;
        },
        py::arg("model"), py::arg("q"), "The wire Jacobian J = d(length)/du (numWires x nu) at q.");
    m.def(
        "calc_wire_generalized_forces",
        [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& tensions) {
            Data data = calcWireGeometry(model, q);
            checkSize(model, tensions, model.getNumWires(), "tensions");
            Eigen::VectorXd tau(model.getNumU());
            calcWireGeneralizedForces(model, data, tensions, tau);
            return tau;
        },
        py::arg("model"), py::arg("q"), py::arg("tensions"),
        "Generalized forces (nu) of wire tensions (N) at q, tau = -J^T f, computed without forming J.");
    m.def(
        "integrate_coordinates",
        [](const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u, double dt) {
            checkSize(model, q, model.getNumQ(), "q");
            checkSize(model, u, model.getNumU(), "u");
            return integrateCoordinates(model, q, u, dt);
        },
        py::arg("model"), py::arg("q"), py::arg("u"), py::arg("dt"),
        "q advanced along u for dt on the configuration manifold (quaternions rotated exactly).");
}

}  // namespace sinew::python
