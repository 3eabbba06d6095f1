#pragma once
// Progress display for long work: a single updating line on a terminal, a log line every
// few seconds otherwise (CI logs, Slurm). Thread-safe: workers call advance().
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace phyir {

// How a Progress line shows its rate. Per second suits fast items (tiles, probes); slow
// ones (dataset views, tens of seconds each) read better per hour: "47 views/hour".
enum class ProgressRate { PerSecond, PerHour };

class Progress {
 public:
  // `enabled` = false makes it silent (tests, nested work).
  Progress(std::string label, uint64_t total, std::string unit = "items", bool enabled = true);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(uint64_t n = 1);
  void finish();  // prints the final line; called by the destructor if not before
  double elapsed_seconds() const;

  // Per second by default; call before the work starts.
  void set_rate(ProgressRate rate) { rate_ = rate; }
  // The text of the current line (no terminal codes): "label: 40% 4/10 views, 47 views/hour,
  // 5m06s elapsed, 7m39s left". `final_line` shows 0s left.
  std::string status_line(bool final_line = false) const;

  // Silences every Progress of the process (test binaries call this once).
  static void set_enabled(bool enabled);

 private:
  void print(bool final_line);

  std::string label_;
  std::string unit_;
  uint64_t total_;
  std::atomic<uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
  std::mutex mutex_;
  bool tty_;
  bool finished_ = false;
  bool enabled_ = true;
  ProgressRate rate_ = ProgressRate::PerSecond;
};

}  // namespace phyir
