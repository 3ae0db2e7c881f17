// sinew.Error, load_model and the Model with its parts and census (core/model.hpp, core/census.hpp,
// io/model_loading.hpp).
#include <pybind11/functional.h>

#include <functional>
#include <memory>

#include "bindings.hpp"
#include "sinew/core/census.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew::python {
namespace {

// None for Model::kNotFound, so that a missing name cannot be taken for an index.
py::object indexOrNone(int index) { return index == Model::kNotFound ? py::object(py::none()) : py::int_(index); }

void bindParts(py::module_& m) {
    py::enum_<JointType>(m, "JointType")
        .value("Free", JointType::Free).value("Ball", JointType::Ball).value("Pin", JointType::Pin)
        .value("Weld", JointType::Weld).value("Custom", JointType::Custom);
    py::enum_<WireKind>(m, "WireKind")
        .value("Muscle", WireKind::Muscle).value("Tendon", WireKind::Tendon)
        .value("Ligament", WireKind::Ligament).value("Cartilage", WireKind::Cartilage);

    py::class_<Link>(m, "Link", "A rigid link (core/model.hpp): mass kg, com_B m, inertia_Bcom kg m^2.")
        .def_readonly("name", &Link::name)
        .def_readonly("mass", &Link::mass)
        .def_readonly("com_B", &Link::com_B)
        .def_readonly("inertia_Bcom", &Link::inertia_Bcom)
        .def_readonly("is_virtual", &Link::isVirtual)
        .def("__repr__", [](const Link& l) { return "<sinew.Link " + l.name + ">"; });
    py::class_<Joint>(m, "Joint", "A link's joint to its parent (parent -1: ground) and its slices of q and u.")
        .def_readonly("name", &Joint::name)
        .def_readonly("type", &Joint::type)
        .def_readonly("parent", &Joint::parent)
        .def_readonly("q_start", &Joint::qStart)
        .def_readonly("nq", &Joint::nq)
        .def_readonly("u_start", &Joint::uStart)
        .def_readonly("nu", &Joint::nu)
        .def("__repr__", [](const Joint& j) { return "<sinew.Joint " + j.name + " (" + toString(j.type) + ")>"; });
    py::class_<Wire>(m, "Wire", "A wire: its points, kind and force law; polyline when it has no OpenSim path features.")
        .def_readonly("name", &Wire::name)
        .def_readonly("kind", &Wire::kind)
        .def_readonly("num_points", &Wire::numPoints)
        .def_property_readonly("force_law", [](const Wire& w) { return w.lawSpec.type; })
        .def_property_readonly("is_polyline", &Wire::isPolyline)
        .def("__repr__", [](const Wire& w) { return "<sinew.Wire " + w.name + " (" + toString(w.kind) + ")>"; });
    py::class_<Loop>(m, "Loop", "A ball-joint loop closure between link_a and link_b.")
        .def_readonly("name", &Loop::name)
        .def_readonly("link_a", &Loop::linkA)
        .def_readonly("p_A", &Loop::p_A)
        .def_readonly("link_b", &Loop::linkB)
        .def_readonly("p_B", &Loop::p_B);
    py::class_<Coordinate>(m, "Coordinate", "One entry of q: its joint, default value and range (rad or m).")
        .def_readonly("name", &Coordinate::name)
        .def_readonly("joint", &Coordinate::joint)
        .def_readonly("default_value", &Coordinate::defaultValue)
        .def_readonly("range_min", &Coordinate::rangeMin)
        .def_readonly("range_max", &Coordinate::rangeMax);

    py::class_<Census>(m, "Census", "The model census of the paper's Table 1 (what `sinew info` prints).")
        .def_readonly("links", &Census::links)
        .def_readonly("virtual_links", &Census::virtualLinks)
        .def_readonly("dof", &Census::dof)
        .def_readonly("dof_with_virtual", &Census::dofWithVirtual)
        .def_readonly("muscles", &Census::muscles)
        .def_readonly("tendons", &Census::tendons)
        .def_readonly("ligaments", &Census::ligaments)
        .def_readonly("cartilage", &Census::cartilage)
        .def_readonly("wires", &Census::wires)
        .def_readonly("wire_points", &Census::wirePoints)
        .def_readonly("loops", &Census::loops);
}

}  // namespace

void bindModel(py::module_& m) {
    // pybind11 tries the translator registered last first, so ModelError (a subclass) comes after Error.
    auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
    py::register_exception<ModelError>(m, "ModelError", error.ptr());
    bindParts(m);

    // shared_ptr holder: the analyses that keep a reference to the model (TensionAnalysis,
    // ForwardDynamics) hold it alive through keep_alive.
    py::class_<Model, std::shared_ptr<Model>>(m, "Model", "An immutable sinew model (core/model.hpp).")
        .def_property_readonly("name", &Model::getName)
        .def_property_readonly("nq", &Model::getNumQ)
        .def_property_readonly("nu", &Model::getNumU)
        .def_property_readonly("num_links", &Model::getNumLinks)
        .def_property_readonly("num_wires", &Model::getNumWires)
        .def_property_readonly("num_loops", &Model::getNumLoops)
        .def_property_readonly("links", &Model::getLinks)
        .def_property_readonly("joints", &Model::getJoints)
        .def_property_readonly("wires", &Model::getWires)
        .def_property_readonly("loops", &Model::getLoops)
        .def_property_readonly("coordinates", &Model::getCoordinates)
        .def_property_readonly("link_names", [](const Model& model) {
            std::vector<std::string> names;
            for (const Link& link : model.getLinks()) names.push_back(link.name);
            return names;
        })
        .def_property_readonly("wire_names", [](const Model& model) {
            std::vector<std::string> names;
            for (const Wire& wire : model.getWires()) names.push_back(wire.name);
            return names;
        })
        .def_property_readonly("coordinate_names", &getCoordinateNames, "Column names of q (nq).")
        .def_property_readonly("speed_names", &getSpeedNames, "Column names of u (nu).")
        // Read-only views into the model, no copies.
        .def_property_readonly("gravity", &Model::getGravity, py::return_value_policy::reference_internal)
        .def_property_readonly("default_q", &Model::getDefaultQ, py::return_value_policy::reference_internal,
                               "The model file's initial pose (nq), a read-only view.")
        .def("census", &calcCensus)
        .def("find_link", [](const Model& model, const std::string& name) { return indexOrNone(model.findLinkIndex(name)); },
             "Link index, -1 for ground, None when absent.")
        .def("find_wire", [](const Model& model, const std::string& name) { return indexOrNone(model.findWireIndex(name)); })
        .def("find_coordinate",
             [](const Model& model, const std::string& name) { return indexOrNone(model.findCoordinateIndex(name)); },
             "Index in q, None when absent.")
        .def("__repr__", [](const Model& model) {
            return "<sinew.Model " + model.getName() + ": " + std::to_string(model.getNumLinks()) + " links, nq " +
                   std::to_string(model.getNumQ()) + ", nu " + std::to_string(model.getNumU()) + ", " +
                   std::to_string(model.getNumWires()) + " wires>";
        });

    m.def(
        "load_model",
        [](const std::string& path, const std::function<void(const std::string&)>& notes) {
            return std::make_shared<Model>(loadModel(path, notes ? notes : [](const std::string&) {}));
        },
        py::arg("path"), py::arg("notes") = nullptr,
        "Reads a sinew YAML model, an OpenSim .osim or an MJCF file (chosen by content). notes(line) receives "
        "what a converter left out. Raises sinew.Error (sinew.ModelError for a bad model, naming file:line).");
}

}  // namespace sinew::python
