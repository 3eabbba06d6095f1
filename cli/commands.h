#pragma once
// Each subcommand registers itself on the top-level app. The callbacks throw
// phyir::Error for user-facing failures; main() prints them and exits with 1.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace phyir::cli {

void add_scenes_command(CLI::App& app);
void add_scenes_info_command(CLI::App& scenes);      // command_scenes_info.cpp
void add_scenes_generate_command(CLI::App& scenes);  // command_scenes_generate.cpp
void add_scenes_sky_command(CLI::App& scenes);       // command_scenes_sky.cpp
void add_render_command(CLI::App& app);
void add_dataset_command(CLI::App& app);
void add_train_command(CLI::App& app);
void add_train_slurm_command(CLI::App& train);      // command_train_slurm.cpp
void add_infer_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_insert_command(CLI::App& app);             // command_insert.cpp
void add_bench_probes_command(CLI::App& bench);      // command_bench_probes.cpp
void add_bench_model_command(CLI::App& bench);       // command_bench_model.cpp
void add_bench_suite_command(CLI::App& bench);       // command_bench_suite.cpp
void add_bench_insert_command(CLI::App& bench);      // command_bench_insert.cpp
void add_assets_command(CLI::App& app);             // command_assets*.cpp

// This process's command line without the program name (main() records it): commands that
// start copies of themselves (train --nproc) repeat it.
void set_command_line(int argc, char** argv);
const std::vector<std::string>& command_line();

// This executable's absolute path, for the scripts a command writes (Slurm jobs run it).
std::filesystem::path this_executable();

// For commands whose issue has not landed: exits with status 3 and says so.
[[noreturn]] void not_yet_available(const std::string& command, int issue);

}  // namespace phyir::cli
