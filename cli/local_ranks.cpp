// Local data-parallel ranks as child processes (local_ranks.h).
#include "local_ranks.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "phyir/core/error.h"
#include "phyir/core/log.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

// Runs in the forked child: never returns.
[[noreturn]] void exec_rank(const std::vector<std::string>& args, const fs::path& log) {
  // A rank must not outlive the launcher (killed, or Ctrl-C): it gets SIGTERM with it.
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (!log.empty()) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
      ::close(fd);
    }
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv("/proc/self/exe", argv.data());
  std::fprintf(stderr, "phyir: cannot run /proc/self/exe: %s\n", std::strerror(errno));
  ::_exit(127);
}

std::string describe(int status) {
  if (WIFEXITED(status)) return fmt::format("exited with status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("was killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  return "ended";
}

}  // namespace

std::vector<std::string> without_option(const std::vector<std::string>& arguments, const std::string& option) {
  std::vector<std::string> out;
  for (size_t i = 0; i < arguments.size(); ++i) {
    if (arguments[i] == option) {
      ++i;  // and its value
      continue;
    }
    if (arguments[i].rfind(option + "=", 0) == 0) continue;
    out.push_back(arguments[i]);
  }
  return out;
}

void run_local_ranks(int nproc, const std::vector<std::string>& arguments, const fs::path& out_dir) {
  if (nproc < 2) fail("--nproc {}: local data-parallel training needs at least 2 processes", nproc);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) fail("{}: cannot create: {}", out_dir.string(), ec.message());
  // A fresh file per launch: a store file left by a killed run would mislead the new ranks.
  const fs::path store = fs::absolute(out_dir / fmt::format(".rendezvous-{}", ::getpid()));
  fs::remove(store, ec);
  spdlog::info("train: {} local ranks meeting at {}; rank 0 prints here, ranks 1-{} log to {}/rank-<r>.log", nproc,
               store.string(), nproc - 1, out_dir.string());
  std::map<pid_t, int> running;
  for (int r = 0; r < nproc; ++r) {
    std::vector<std::string> args = {"phyir"};
    args.insert(args.end(), arguments.begin(), arguments.end());
    args.insert(args.end(), {"--world-size", std::to_string(nproc), "--rank", std::to_string(r), "--rendezvous",
                             "file:" + store.string()});
    const fs::path log = r == 0 ? fs::path() : out_dir / fmt::format("rank-{}.log", r);
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) fail("train --nproc: cannot start rank {}: {}", r, std::strerror(errno));
    if (pid == 0) exec_rank(args, log);
    running[pid] = r;
  }
  std::string failure;
  while (!running.empty()) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    auto it = running.find(pid);
    if (it == running.end()) continue;
    const int rank = it->second;
    running.erase(it);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;
    if (!failure.empty()) continue;  // the others' errors follow from the first
    failure = fmt::format("rank {} {}{}", rank, describe(status),
                          rank == 0 ? std::string() : fmt::format(" (its log: {})", (out_dir / fmt::format("rank-{}.log", rank)).string()));
    for (const auto& [other, _] : running) {
      ::kill(other, SIGTERM);
      ::kill(other, SIGCONT);  // a stopped rank ends too
    }
  }
  fs::remove(store, ec);
  if (!failure.empty()) fail("train --nproc {}: {}; the other ranks were stopped", nproc, failure);
}

}  // namespace phyir::cli
