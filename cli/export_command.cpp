#include <cstdio>

#include "arguments.hpp"
#include "commands.hpp"
#include "sinew/io/mjcf_model_writer.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew export MODEL -o MODEL.xml\n"
    "  Writes the model as MuJoCo MJCF (docs/mjcf-export.md): links as bodies at the default pose, ball, pin\n"
    "  and free joints, loops as connect equalities, polyline wires as spatial tendons (spring-dampers as\n"
    "  tendon springs). Lists how MuJoCo's model differs; refuses what MJCF cannot say, naming it.\n";

}  // namespace

int runExport(const std::vector<std::string>& args) {
    std::string input, output;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("-o", "--output")) output = reader.value();
        else reader.takePositional({&input});
    }
    if (reader.helpShown()) return 0;
    if (input.empty() || output.empty()) return reader.failWithUsage();
    const Model model = loadModel(input, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    for (const std::string& note : writeMjcfModel(model, output)) std::printf("note: %s\n", note.c_str());
    std::printf("exported %s: %d bodies, %d DOF, %d loops as connects, %d tendons -> %s\n", model.getName().c_str(),
                model.getNumLinks(), model.getNumU(), model.getNumLoops(), model.getNumWires(), output.c_str());
    return 0;
}

}  // namespace sinew::cli
