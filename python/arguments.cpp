// Argument checks shared by the bindings (bindings.hpp).
#include "sinew/core/error.hpp"
#include "bindings.hpp"

namespace sinew::python {

void checkSize(const Model& model, const Eigen::VectorXd& v, Eigen::Index expected, const char* what) {
    if (v.size() != expected)
        throw Error(std::string(what) + " has " + std::to_string(v.size()) + " entries; model '" + model.getName() +
                    "' expects " + std::to_string(expected));
}

std::vector<SpatialVector> toLinkForces(const Model& model, const std::optional<Eigen::MatrixXd>& forces) {
    const int n = model.getNumLinks();
    std::vector<SpatialVector> linkForces(static_cast<std::size_t>(n), SpatialVector::Zero());
    if (!forces) return linkForces;
    if (forces->rows() != n || forces->cols() != 6)
        throw Error("link_forces is " + std::to_string(forces->rows()) + " x " + std::to_string(forces->cols()) +
                    "; model '" + model.getName() + "' expects " + std::to_string(n) +
                    " x 6 (per link: moment about its origin, force; ground axes)");
    for (int i = 0; i < n; ++i) linkForces[static_cast<std::size_t>(i)] = forces->row(i).transpose();
    return linkForces;
}

int findLinkOrThrow(const Model& model, const std::string& name, const char* what) {
    const int link = model.findLinkIndex(name);
    if (link < 0)
        throw Error(std::string(what) + " expects a link of model '" + model.getName() + "', got '" + name + "'");
    return link;
}

}  // namespace sinew::python
