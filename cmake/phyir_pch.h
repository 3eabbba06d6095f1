#pragma once
// The precompiled header of the toolkit's libraries, CLI and tests (cmake/Precompile.cmake):
// the third-party and standard headers most of their files include. json and TBB take 2-4 s
// each to parse; parsed once per target instead of once per file, they take 15-25% off a cold
// build of those targets (docs/building.md), which is what CI does from its clean clone.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>
