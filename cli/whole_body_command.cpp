#include <cstdio>

#include "arguments.hpp"
#include "commands.hpp"
#include "sinew/core/census.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/tools/whole_body_model.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew whole-body SOURCE --rules RULES.yaml [--anthropometrics DUMAS.csv] -o MODEL.yaml\n"
    "  Derives sinew's whole-body wire model from a detailed source model (MS-Human-700's MJCF) by the rules\n"
    "  file: bodies grouped into links on ball joints, loops, forked muscles through virtual links, ligaments\n"
    "  and cartilage, every wire a passive spring-damper (docs/whole-body-model.md). The table completes the\n"
    "  masses the source lacks.\n";

}  // namespace

int runWholeBody(const std::vector<std::string>& args) {
    std::string source, rulesPath, tablePath, output;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("-o", "--output")) output = reader.value();
        else if (reader.is("--rules")) rulesPath = reader.value();
        else if (reader.is("--anthropometrics")) tablePath = reader.value();
        else reader.takePositional({&source});
    }
    if (reader.helpShown()) return 0;
    if (source.empty() || rulesPath.empty() || output.empty()) return reader.failWithUsage();
    const Model sourceModel = loadModel(source, [](const std::string&) {});
    const WholeBodyRules rules = readWholeBodyRules(rulesPath);
    std::optional<SegmentRatios> ratios;
    if (rules.missingMass) {
        if (tablePath.empty()) throw Error("the rules complete missing masses: give --anthropometrics DUMAS.csv");
        ratios = readSegmentRatios(tablePath, rules.missingMass->segment, rules.missingMass->gender);
    }
    const WholeBodyBuild built = buildWholeBodyModel(sourceModel, rules, ratios);
    for (const std::string& note : built.notes) std::printf("note: %s\n", note.c_str());
    writeModelFile(built.model, output);
    const Census census = calcCensus(built.model);
    std::printf("whole body '%s': %d links, %d virtual links, %d loops, %d DOF (%d with virtual links), %d wires "
                "(%d muscles, %d tendons, %d ligaments, %d cartilage) -> %s\n",
                built.model.getName().c_str(), census.links, census.virtualLinks, census.loops, census.dof,
                census.dofWithVirtual, census.wires, census.muscles, census.tendons, census.ligaments,
                census.cartilage, output.c_str());
    return 0;
}

}  // namespace sinew::cli
