// The hand-off of the network's commands to phyir-torch (torch_handoff.h).
#include "torch_handoff.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.h"

namespace phyir::cli {

std::string torch_command(int argc, char** argv) {
  std::vector<std::string> words;  // the command words, without options and --log-level's value
  bool has_model_option = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--model" || a.rfind("--model=", 0) == 0) has_model_option = true;
    if (a == "--log-level") {
      ++i;
      continue;
    }
    if (!a.empty() && a[0] != '-' && words.size() < 2) words.push_back(a);
  }
  if (words.empty()) return "";
  if (words[0] == "train" || words[0] == "infer") return words[0];
  if (words[0] == "bench" && words.size() > 1 && words[1] == "model") return "bench model";
  if (words[0] == "eval" && has_model_option) return "eval --model";
  return "";
}

void run_in_torch_cli(const std::string& command) {
#ifdef PHYIR_TORCH_CLI
  const std::filesystem::path self = this_executable();
  const std::string torch_cli = (self.parent_path() / PHYIR_TORCH_CLI).string();
  // argv[0] stays phyir's path: usage lines and messages name the command the user typed.
  const std::string program = self.string();
  std::vector<char*> args{const_cast<char*>(program.c_str())};
  for (const std::string& a : command_line()) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  ::execv(torch_cli.c_str(), args.data());
  std::fprintf(stderr, "phyir %s: cannot start %s, which runs the network's commands: %s\n", command.c_str(),
               torch_cli.c_str(), std::strerror(errno));
  std::exit(1);
#else
  std::fprintf(stderr, "phyir %s: not available in this build (not built: configured with -DPHYIR_BUILD_MODEL=OFF)\n",
               command.c_str());
  std::exit(3);
#endif
}

std::string torch_build_note() {
#ifdef PHYIR_TORCH_CLI
  return "";
#else
  return " (not built: PHYIR_BUILD_MODEL=OFF)";
#endif
}

}  // namespace phyir::cli
