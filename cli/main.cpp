// sinew: wire-driven musculoskeletal dynamics on Simbody.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.hpp"

namespace {

const char* kUsage =
    "usage: sinew COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  info MODEL                      the model's census (paper's Table 1)\n"
    "  simulate MODEL [--engine sinew|simbody] [--integrator adaptive|rk4] [--step H]\n"
    "                 [--hang-by LINK] [--duration T] [--interval DT] [--accuracy A] [-o DIR]\n"
    "                                  passive forward simulation with sinew's or Simbody's engine;\n"
    "                                  writes .sto files of coordinates, speeds, wire tensions and energy\n"
    "\n"
    "Run 'sinew COMMAND --help' for a command's options.\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    try {
        if (command == "info") return sinew::cli::runInfo(args);
        if (command == "simulate") return sinew::cli::runSimulate(args);
        std::fprintf(stderr, "sinew: unknown command '%s'\n\n%s", command.c_str(), kUsage);
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sinew %s: error: %s\n", command.c_str(), e.what());
        return 1;
    }
}
