#include <cstdio>

#include "arguments.hpp"
#include "commands.hpp"
#include "sinew/core/census.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/osim_model_converter.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew import MODEL.osim -o MODEL.yaml\n"
    "  Converts an OpenSim 4 model into sinew's model file: bodies, joints (as custom joints), coordinates,\n"
    "  muscles as wires with their path points, wrap objects and a Thelen 2003 force law. Lists, by name and\n"
    "  file:line, every element it leaves out.\n";

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
    const OsimConversion conversion = convertOsimModel(readOsimModel(input));
    for (const std::string& line : conversion.notImported) std::printf("not imported: %s\n", line.c_str());
    writeModelFile(conversion.model, output);
    const Census census = calcCensus(conversion.model);
    std::printf("imported %s: %d links, %d DOF, %d wires (%d muscles), %zu wrap objects -> %s\n",
                conversion.model.getName().c_str(), census.links, census.dof, census.wires, census.muscles,
                conversion.model.getWrapObjects().size(), output.c_str());
    return 0;
}

}  // namespace sinew::cli
