#pragma once
// The Python module's pieces, one per concept (docs/python.md), and the argument checks they share. The
// bindings only convert: every number comes from the C++ library. Arrays cross as NumPy arrays through
// pybind11/eigen.h; an Eigen vector or matrix returned by value is moved into its array, not copied.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew::python {

namespace py = pybind11;

void bindModel(py::module_& m);       // sinew.Error, load_model, Model, its census
void bindStorage(py::module_& m);     // StorageTable, .sto/.mot read and write, external loads
void bindKinematics(py::module_& m);  // link poses, wire lengths and speeds, the wire Jacobian
void bindDynamics(py::module_& m);    // inverse dynamics (per frame, per motion), ForwardDynamics
void bindSimulation(py::module_& m);  // forward simulation with sinew's or Simbody's engine
void bindTensions(py::module_& m);    // TensionAnalysis per frame, runTensionAnalysis per motion

// The C++ algorithms take sizes on trust (they assert); a Python caller gets a sinew.Error naming the argument.
void checkSize(const Model& model, const Eigen::VectorXd& v, Eigen::Index expected, const char* what);

// Applied link forces, (numLinks x 6) rows [moment about the link origin; force] in ground axes (the
// Data::F_G convention); none: all zero.
std::vector<SpatialVector> toLinkForces(const Model& model, const std::optional<Eigen::MatrixXd>& forces);

// Link index of `name` (ground refused), for arguments such as hang_by; throws sinew::Error otherwise.
int findLinkOrThrow(const Model& model, const std::string& name, const char* what);

}  // namespace sinew::python
