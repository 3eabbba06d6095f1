#include "phyir/core/machine.h"

#include <sys/resource.h>

#include <fstream>
#include <sstream>
#include <thread>

namespace phyir {

namespace {

// The value of /proc/cpuinfo's first "key : value" line for `key`, or "".
std::string cpuinfo_value(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(key, 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos || line.find_first_not_of(" \t", key.size()) != colon) continue;
    return colon + 2 <= line.size() ? line.substr(colon + 2) : std::string();
  }
  return "";
}

bool has_flag(const std::string& flags, const std::string& flag) {
  return (" " + flags + " ").find(" " + flag + " ") != std::string::npos;
}

}  // namespace

std::string describe_cpu(const std::string& cpuinfo) {
  std::string model = cpuinfo_value(cpuinfo, "model name");
  if (model.empty()) model = "unknown CPU";
  // A VM may show only "AMD EPYC": family and model tell its generation apart (25/1 is Zen 3,
  // 25/17 Zen 4), and the widest vector unit is what the renderer's and Torch's kernels use.
  const std::string family = cpuinfo_value(cpuinfo, "cpu family"), number = cpuinfo_value(cpuinfo, "model");
  const std::string flags = cpuinfo_value(cpuinfo, "flags");
  const char* simd = has_flag(flags, "avx512f") ? "AVX-512" : has_flag(flags, "avx2") ? "AVX2" : nullptr;
  std::string details;
  if (!family.empty() && !number.empty()) details = "family " + family + " model " + number;
  if (simd) details += (details.empty() ? "" : ", ") + std::string(simd);
  return details.empty() ? model : model + " (" + details + ")";
}

std::string machine_description() {
  std::ifstream file("/proc/cpuinfo");
  std::ostringstream text;
  text << file.rdbuf();
  return describe_cpu(text.str()) + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace phyir
