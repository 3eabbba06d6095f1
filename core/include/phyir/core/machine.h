#pragma once
// What a benchmark reports about where it ran: every timing the toolkit writes names its
// machine, and CPU time (which waiting for a loaded machine's cores does not inflate the
// way it does wall time) is measured the same way everywhere.
#include <string>

namespace phyir {

// "AMD EPYC ..., 2 hardware threads": the CPU model of /proc/cpuinfo and the thread count.
std::string machine_description();

// User + system CPU seconds of this process so far (all threads).
double process_cpu_seconds();

}  // namespace phyir
