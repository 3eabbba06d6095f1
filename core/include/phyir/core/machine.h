#pragma once
// What a benchmark reports about where it ran: every timing the toolkit writes names its
// machine, and CPU time (which waiting for a loaded machine's cores does not inflate the
// way it does wall time) is measured the same way everywhere.
#include <string>

namespace phyir {

// "AMD EPYC (family 25 model 1, AVX2), 2 hardware threads": the CPU of /proc/cpuinfo and
// the thread count.
std::string machine_description();

// The CPU part of machine_description() from the text of a /proc/cpuinfo: the first
// processor's model name, then its family, model and widest vector unit where given.
std::string describe_cpu(const std::string& cpuinfo);

// User + system CPU seconds of this process so far (all threads).
double process_cpu_seconds();

}  // namespace phyir
