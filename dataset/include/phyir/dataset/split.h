#pragma once
// Train / val / test by scene: every view of a scene is in its scene's split, so no scene
// is seen in two splits. A scene's split depends only on (its name, the seed, the
// fractions): u = hash_unit("phyir-dataset split|<seed>|<name>") in [0, 1) is train below
// `train`, val below `train + val`, test above. Adding scenes to a dataset never moves the
// others; with few scenes the realised fractions can differ from the asked ones.
#include <cstdint>
#include <string>

#include "phyir/dataset/settings.h"

namespace phyir::dataset {

enum class Split { Train, Val, Test };

const char* split_name(Split split);  // "train", "val", "test"

Split split_for_scene(const std::string& scene_name, uint64_t seed, const SplitFractions& fractions);

}  // namespace phyir::dataset
