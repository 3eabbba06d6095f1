#include "phyir/core/machine.h"

#include <gtest/gtest.h>

namespace phyir {
namespace {

// Two VMs that both call themselves "AMD EPYC" ran the probes 1.6x apart: the description
// must tell their generations apart.
TEST(Machine, DescribesTheCpusGenerationAndVectorUnit) {
  const std::string zen3 =
      "processor\t: 0\nvendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 1\nmodel name\t: AMD EPYC\n"
      "flags\t\t: fpu sse sse2 avx avx2 fma\n\nprocessor\t: 1\ncpu family\t: 25\nmodel\t\t: 1\n";
  EXPECT_EQ(describe_cpu(zen3), "AMD EPYC (family 25 model 1, AVX2)");
  const std::string zen4 = "cpu family\t: 25\nmodel\t\t: 17\nmodel name\t: AMD EPYC\nflags\t\t: avx2 avx512f avx512bw\n";
  EXPECT_EQ(describe_cpu(zen4), "AMD EPYC (family 25 model 17, AVX-512)");
  // "model name" is not "model"; flags are whole words (avx512fp16 alone is not avx512f).
  EXPECT_EQ(describe_cpu("model name\t: X\nflags\t\t: avx512fp16\n"), "X");
  EXPECT_EQ(describe_cpu(""), "unknown CPU");
}

TEST(Machine, DescriptionOfThisMachineNamesItsThreads) {
  EXPECT_NE(machine_description().find("hardware threads"), std::string::npos);
}

}  // namespace
}  // namespace phyir
