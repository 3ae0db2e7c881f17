#include <cstdio>

#include "commands.hpp"
#include "sinew/core/census.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew::cli {

int runInfo(const std::vector<std::string>& args) {
    if (args.size() != 1 || args[0] == "--help") {
        std::fputs("usage: sinew info MODEL\n  Prints the model's census: links, virtual links, DOF, wires by kind, loops.\n",
                   args.size() == 1 ? stdout : stderr);
        return args.size() == 1 ? 0 : 2;
    }
    const Model model = readModelFile(args[0]);
    const Census c = calcCensus(model);
    std::printf("model %s (%s)\n", model.getName().c_str(), args[0].c_str());
    std::printf("  %-28s %6d\n", "links", c.links);
    std::printf("  %-28s %6d\n", "virtual links", c.virtualLinks);
    std::printf("  %-28s %6d\n", "DOF", c.dof);
    std::printf("  %-28s %6d\n", "DOF with virtual links", c.dofWithVirtual);
    std::printf("  %-28s %6d\n", "muscles", c.muscles);
    std::printf("  %-28s %6d\n", "tendons", c.tendons);
    std::printf("  %-28s %6d\n", "ligaments", c.ligaments);
    std::printf("  %-28s %6d\n", "cartilage", c.cartilage);
    std::printf("  %-28s %6d\n", "wires (total)", c.wires);
    std::printf("  %-28s %6d\n", "wire points", c.wirePoints);
    std::printf("  %-28s %6d\n", "loops", c.loops);
    return 0;
}

}  // namespace sinew::cli
