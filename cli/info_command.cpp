#include <cstdio>

#include "commands.hpp"
#include "sinew/core/census.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew::cli {

int runInfo(const std::vector<std::string>& args) {
    if (args.size() != 1 || args[0] == "--help") {
        std::fputs("usage: sinew info MODEL\n  Prints the model's census: links, virtual links, DOF, wires by kind, loops. MODEL is a sinew\n"
                   "  YAML model, an OpenSim .osim or an MJCF file (converted on the fly, what is left out listed).\n",
                   args.size() == 1 ? stdout : stderr);
        return args.size() == 1 ? 0 : 2;
    }
    const Model model = loadModel(args[0], [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    const Census c = calcCensus(model);
    std::printf("model %s (%s)\n", model.getName().c_str(), args[0].c_str());
    // The paper's Table 1 (Nakamura et al.'s whole-body model) beside it; it gives no wire-point or loop count.
    struct Row {
        const char* what;
        int value;
        int paper;
    };
    const Row rows[] = {{"links", c.links, 53},           {"virtual links", c.virtualLinks, 28},
                        {"DOF", c.dof, 153},              {"DOF with virtual links", c.dofWithVirtual, 321},
                        {"muscles", c.muscles, 366},      {"tendons", c.tendons, 91},
                        {"ligaments", c.ligaments, 34},   {"cartilage", c.cartilage, 56},
                        {"wires (total)", c.wires, 547},  {"wire points", c.wirePoints, -1},
                        {"loops", c.loops, -1},           {"force elements", c.forceElements, -1}};
    std::printf("  %-28s %6s %8s\n", "", "model", "paper");
    for (const Row& row : rows) {
        if (row.paper < 0) std::printf("  %-28s %6d %8s\n", row.what, row.value, "-");
        else std::printf("  %-28s %6d %8d\n", row.what, row.value, row.paper);
    }
    return 0;
}

}  // namespace sinew::cli
