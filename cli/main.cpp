// phyir: the toolkit's single command-line entry point.
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "commands.h"
#include "flag_registry.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "torch_handoff.h"

namespace phyir::cli {

void not_yet_available(const std::string& command, int issue) {
  std::fprintf(stderr, "phyir %s: not yet available (arrives with issue %d)\n", command.c_str(), issue);
  std::exit(3);
}

namespace {
std::vector<std::string> recorded_command_line;
}  // namespace

void set_command_line(int argc, char** argv) { recorded_command_line.assign(argv + 1, argv + argc); }

const std::vector<std::string>& command_line() { return recorded_command_line; }

std::filesystem::path this_executable() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) fail("cannot find the phyir binary (/proc/self/exe); pass --phyir PATH");
  return self;
}

}  // namespace phyir::cli

int main(int argc, char** argv) {
  phyir::init_logging();
  phyir::cli::set_command_line(argc, argv);
#if defined(PHYIR_TORCH_CLI) && !defined(PHYIR_HAVE_MODEL)
  // The network's commands, --help included, are phyir-torch's (torch_handoff.h).
  const std::string torch_command = phyir::cli::torch_command(argc, argv);
  if (!torch_command.empty()) phyir::cli::run_in_torch_cli(torch_command);
#endif
  CLI::App app{"phyir: physically based inverse rendering of indoor panoramas.\n"
               "Scenes in (glTF 2.0), HDR panoramas, AOVs and light probes out, the PhyIR "
               "network trained and evaluated on them."};
  app.set_version_flag("--version", std::string("phyir ") + PHYIR_VERSION);
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->capture_default_str();
  app.require_subcommand(1);
  app.fallthrough();  // global options (--log-level) also work after the subcommand
  app.parse_complete_callback([&] { phyir::set_log_level(log_level); });

  phyir::cli::add_scenes_command(app);
  phyir::cli::add_assets_command(app);
  phyir::cli::add_render_command(app);
  phyir::cli::add_dataset_command(app);
  phyir::cli::add_train_command(app);
  phyir::cli::add_infer_command(app);
  phyir::cli::add_eval_command(app);
  phyir::cli::add_bench_command(app);
  phyir::cli::add_insert_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::RequiredError& e) {
    // CLI11 says only "A subcommand is required" when a word is not a command: name it.
    CLI::App* current = &app;
    std::string path = "phyir";
    for (int i = 1; i < argc; ++i) {
      const std::string word = argv[i];
      if (word.empty() || word[0] == '-' || (i > 1 && std::string(argv[i - 1]) == "--log-level")) continue;
      CLI::App* next = nullptr;
      std::string names;
      for (CLI::App* sub : current->get_subcommands({})) {
        if (sub->get_name() == word) next = sub;
        names += (names.empty() ? "" : ", ") + sub->get_name();
      }
      if (next) {
        current = next;
        path += " " + word;
        continue;
      }
      if (names.empty()) break;  // a positional argument of a command: not ours to judge
      std::fprintf(stderr, "phyir: error: '%s' is not a command of '%s' (commands: %s; see %s --help)\n",
                   word.c_str(), path.c_str(), names.c_str(), path.c_str());
      return 1;
    }
    return app.exit(e, std::cout, std::cerr);
  } catch (const CLI::ParseError& e) {
    return app.exit(e, std::cout, std::cerr);
  } catch (const phyir::SettingError& e) {
    // A library names the setting; the user gave a flag (flag_registry.h).
    std::fprintf(stderr, "phyir: error: %s\n", phyir::cli::setting_error_message(app, e).c_str());
    return 1;
  } catch (const phyir::Error& e) {
    std::fprintf(stderr, "phyir: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "phyir: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
