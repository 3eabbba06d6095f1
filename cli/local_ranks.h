#pragma once
// `phyir train --nproc N`: one training as N processes on this machine, ranks 0..N-1, meeting
// at a rendezvous file in the output folder (docs/model-scale.md "Training on several processes").
// Rank 0 writes to this terminal, rank r > 0 to OUT/rank-<r>.log. When a rank fails, the others
// are stopped and the error names the rank, how it ended and its log.
#include <filesystem>
#include <string>
#include <vector>

namespace phyir::cli {

// `arguments`: the command line (argv[1..]) without --nproc; rank r runs this executable with
// it and --world-size N --rank r --rendezvous file:OUT/.rendezvous-<pid>. Throws phyir::Error
// when a rank fails (after every rank has ended).
void run_local_ranks(int nproc, const std::vector<std::string>& arguments, const std::filesystem::path& out_dir);

// The command line without `option` and its value (as "--option V" or "--option=V").
std::vector<std::string> without_option(const std::vector<std::string>& arguments, const std::string& option);

}  // namespace phyir::cli
