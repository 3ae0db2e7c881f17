#include <cstdio>

#include "arguments.hpp"
#include "commands.hpp"
#include "sinew/core/census.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew import MODEL -o MODEL.yaml\n"
    "  Converts an OpenSim 4 model (.osim) or a MuJoCo MJCF model (.xml), told apart by their content, into\n"
    "  sinew's model file: bodies, joints (as custom joints), coordinates, muscles and tendons as wires with\n"
    "  their path points and wrap objects, and a Thelen 2003 muscle law (docs/opensim-import.md,\n"
    "  docs/mjcf-import.md). Lists, by name and file:line, every element it leaves out.\n";

}  // namespace

int runImport(const std::vector<std::string>& args) {
    std::string input, output;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("-o", "--output")) output = reader.value();
        else reader.takePositional({&input});
    }
    if (reader.helpShown()) return 0;
    if (input.empty() || output.empty()) return reader.failWithUsage();
    const Model model = loadModel(input, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    writeModelFile(model, output);
    const Census census = calcCensus(model);
    std::printf("imported %s: %d links, %d DOF, %d wires (%d muscles), %zu wrap objects -> %s\n",
                model.getName().c_str(), census.links, census.dof, census.wires, census.muscles,
                model.getWrapObjects().size(), output.c_str());
    return 0;
}

}  // namespace sinew::cli
