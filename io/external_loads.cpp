#include "sinew/io/external_loads.hpp"

#include "osim_xml.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using osim::Element;
using osim::XmlDocument;

// The three columns whose labels start with `identifier` (OpenSim's Storage::getColumnIndicesForIdentifier).
std::array<int, 3> findColumns(const XmlDocument& doc, const Element& force, const char* property,
                               const std::string& identifier, const ExternalLoads& loads) {
    std::array<int, 3> columns{-1, -1, -1};
    if (identifier.empty()) return columns;
    std::vector<int> found;
    std::string labels;
    for (std::size_t c = 0; c < loads.data.columns.size(); ++c)
        if (loads.data.columns[c].compare(0, identifier.size(), identifier) == 0) {
            found.push_back(static_cast<int>(c));
            labels += (labels.empty() ? "" : ", ") + loads.data.columns[c];
        }
    if (found.size() != 3)
        doc.fail(*osim::findChild(force, property),
                 "'" + identifier + "' starts " + std::to_string(found.size()) + " column labels of " + loads.dataFile +
                     (labels.empty() ? "" : " (" + labels + ")") + "; expected exactly 3, its x, y and z");
    std::copy(found.begin(), found.end(), columns.begin());
    return columns;
}

ExternalForce readExternalForce(const XmlDocument& doc, const Element& element, const ExternalLoads& loads) {
    ExternalForce force;
    force.name = osim::getName(element);
    force.where = doc.where(element);
    force.appliesForce = osim::readAppliesForce(doc, element, force.appliesForce);
    force.appliedToBody = osim::readText(doc, element, "applied_to_body");
    if (force.appliedToBody.empty()) doc.fail(element, "missing <applied_to_body>");
    force.forceExpressedInBody = osim::readText(doc, element, "force_expressed_in_body", force.forceExpressedInBody);
    force.pointExpressedInBody = osim::readText(doc, element, "point_expressed_in_body", force.pointExpressedInBody);
    force.forceIdentifier = osim::readText(doc, element, "force_identifier");
    force.pointIdentifier = osim::readText(doc, element, "point_identifier");
    force.torqueIdentifier = osim::readText(doc, element, "torque_identifier");
    force.dataSourceName = osim::readText(doc, element, "data_source_name");
    // The same consistency rules as OpenSim's ExternalForce::extendConnectToModel.
    if (force.forceIdentifier.empty() && force.torqueIdentifier.empty())
        doc.fail(element, "applies neither a force nor a torque (no force_identifier or torque_identifier)");
    if (force.forceIdentifier.empty() && !force.pointIdentifier.empty())
        doc.fail(element, "has a point_identifier but no force_identifier");
    force.forceColumns = findColumns(doc, element, "force_identifier", force.forceIdentifier, loads);
    force.pointColumns = findColumns(doc, element, "point_identifier", force.pointIdentifier, loads);
    force.torqueColumns = findColumns(doc, element, "torque_identifier", force.torqueIdentifier, loads);
    return force;
}

}  // namespace

ExternalLoads readExternalLoads(const std::string& path) {
    const XmlDocument doc(path);
    const Element& root = doc.getObject("ExternalLoads");
    ExternalLoads loads;
    loads.name = osim::getName(root);
    loads.file = path;
    loads.dataFile = doc.resolveFile(osim::readText(doc, root, "datafile"));
    if (loads.dataFile.empty()) doc.fail(root, "missing <datafile>, the storage file the forces are read from");
    loads.data = readStorageFile(loads.dataFile);
    loads.modelKinematicsFile = doc.resolveFile(osim::readText(doc, root, "external_loads_model_kinematics_file"));
    loads.lowpassCutoffFrequencyForLoadKinematics = osim::readDouble(
        doc, root, "lowpass_cutoff_frequency_for_load_kinematics", loads.lowpassCutoffFrequencyForLoadKinematics);
    for (const Element* element : osim::getSetObjects(root)) {
        if (std::string(osim::typeOf(*element)) != "ExternalForce") doc.fail(*element, "expected an <ExternalForce>");
        loads.forces.push_back(readExternalForce(doc, *element, loads));
    }
    return loads;
}

void checkExternalLoadsBodies(const ExternalLoads& loads, const OsimModel& model) {
    for (const ExternalForce& force : loads.forces)
        for (const std::string* body : {&force.appliedToBody, &force.forceExpressedInBody, &force.pointExpressedInBody})
            if (*body != model.ground.name && !findBody(model, *body))
                throw ModelError(force.where, "external force '" + force.name + "' names body '" + *body +
                                                  "', which is not in " + model.file);
}

}  // namespace sinew
