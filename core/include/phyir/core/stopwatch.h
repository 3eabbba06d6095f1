#pragma once
// Wall-clock seconds since a start, for the timings records report (render.json, bench
// outputs). Steady clock: never jumps with the system time.
#include <chrono>

namespace phyir {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace phyir
