#pragma once
// Long statistical tests (seconds of rendering to reach a tight tolerance) are skipped in the
// sanitizer build of scripts/sanitize.sh (PHYIR_SANITIZE, which defines PHYIR_SANITIZED for
// the tests): there they run 5-6 times slower, and the code they reach runs under the
// sanitizers in shorter tests, which the skip message names.
#include <gtest/gtest.h>

#ifdef PHYIR_SANITIZED
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif

// PHYIR_SKIP_UNDER_SANITIZERS("the other ProbeCache tests"): the first line of such a test.
#define PHYIR_SKIP_UNDER_SANITIZERS(covered_by) \
  if (kUnderSanitizers) GTEST_SKIP() << "long statistical test, skipped under the sanitizers; covered there by " covered_by
