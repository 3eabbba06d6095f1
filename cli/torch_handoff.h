#pragma once
// `phyir` is built without LibTorch (cli/CMakeLists.txt): the network's commands run in
// `phyir-torch`, the same CLI built with it, which phyir starts in its own place (exec) with
// the same arguments.
#include <string>

namespace phyir::cli {

// The command of the command line (argv[1..]) when it needs the network ("train", "infer",
// "bench model", "eval --model"), else "". Global options (--log-level V) may come first.
std::string torch_command(int argc, char** argv);

// Replaces this process by phyir-torch with this process's arguments (command_line()); when
// this build has no network (PHYIR_BUILD_MODEL=OFF), says so and exits with status 3.
[[noreturn]] void run_in_torch_cli(const std::string& command);

// " (not built: PHYIR_BUILD_MODEL=OFF)" for the network's commands in a build without it.
std::string torch_build_note();

}  // namespace phyir::cli
