#include "phyir/dataset/split.h"

#include <fmt/format.h>

#include "phyir/dataset/checksum.h"

namespace phyir::dataset {

const char* split_name(Split split) {
  switch (split) {
    case Split::Train: return "train";
    case Split::Val: return "val";
    case Split::Test: return "test";
  }
  return "?";
}

Split split_for_scene(const std::string& scene_name, uint64_t seed, const SplitFractions& fractions) {
  const double u = hash_unit(fmt::format("phyir-dataset split|{}|{}", seed, scene_name));
  if (u < fractions.train) return Split::Train;
  if (u < fractions.train + fractions.val) return Split::Val;
  return Split::Test;
}

}  // namespace phyir::dataset
