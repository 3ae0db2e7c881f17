// The Python module `sinew` (docs/python.md): one binding file per concept, registered here.
#include "bindings.hpp"

PYBIND11_MODULE(sinew, m) {
    m.doc() = "sinew: wire-driven musculoskeletal dynamics (models, kinematics, wire Jacobian, forward and "
              "inverse dynamics, tensions from motion, OpenSim storage files). Arrays are NumPy arrays.";
    sinew::python::bindModel(m);
    sinew::python::bindStorage(m);
    sinew::python::bindKinematics(m);
    sinew::python::bindDynamics(m);
    sinew::python::bindSimulation(m);
    sinew::python::bindTensions(m);
}
