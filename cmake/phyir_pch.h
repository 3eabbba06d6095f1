#pragma once
// The precompiled header of the toolkit's libraries, CLI and tests (cmake/Precompile.cmake):
// the third-party and standard headers most of their files include. json, TBB and glm take
// 1.5-4 s each to parse; compiled once per target instead of once per file, they are the
// largest part of a cold build saved (CI builds from a clean clone, without ccache's help).
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
