#include "phyir/core/progress.h"

#include <unistd.h>

#include <cstdio>

#include "phyir/core/log.h"

namespace phyir {

namespace {
std::atomic<bool> g_enabled{true};

std::string format_seconds(double s) {
  if (s < 0 || s > 1e7) return "?";
  char buf[32];
  if (s < 60) std::snprintf(buf, sizeof buf, "%.0fs", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) / 60) % 60);
  return buf;
}
}  // namespace

void Progress::set_enabled(bool enabled) { g_enabled = enabled; }

Progress::Progress(std::string label, uint64_t total, std::string unit, bool enabled)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total),
      start_(std::chrono::steady_clock::now()), last_print_(start_),
      tty_(::isatty(STDERR_FILENO) != 0), enabled_(enabled) {}

Progress::~Progress() { finish(); }

double Progress::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::advance(uint64_t n) {
  done_ += n;
  if (!g_enabled || !enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  // Terminals redraw 5 times a second; logs get a line every 10 s.
  const double interval = tty_ ? 0.2 : 10.0;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  if (std::chrono::duration<double>(now - last_print_).count() < interval) return;
  last_print_ = now;
  print(false);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (g_enabled && enabled_) print(true);
}

std::string Progress::status_line(bool final_line) const {
  const uint64_t done = done_.load();
  const double elapsed = elapsed_seconds();
  const double fraction = total_ ? double(done) / double(total_) : 1.0;
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  const double left = rate > 0 ? (total_ - done) / rate : -1.0;
  char rate_text[64];
  if (rate_ == ProgressRate::PerHour)
    std::snprintf(rate_text, sizeof rate_text, "%.0f %s/hour", 3600.0 * rate, unit_.c_str());
  else
    std::snprintf(rate_text, sizeof rate_text, "%.1f %s/s", rate, unit_.c_str());
  char line[256];
  std::snprintf(line, sizeof line, "%s: %3.0f%% %llu/%llu %s, %s, %s elapsed, %s left", label_.c_str(),
                100.0 * fraction, (unsigned long long)done, (unsigned long long)total_, unit_.c_str(), rate_text,
                format_seconds(elapsed).c_str(), final_line ? "0s" : format_seconds(left).c_str());
  return line;
}

void Progress::print(bool final_line) {
  const std::string text = status_line(final_line);
  const char* line = text.c_str();
  if (tty_) {
    std::fprintf(stderr, "\r\033[K%s%s", line, final_line ? "\n" : "");
    std::fflush(stderr);
  } else {
    spdlog::info("{}", line);
  }
}

}  // namespace phyir
