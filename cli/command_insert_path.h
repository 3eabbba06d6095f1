#pragma once
// Dynamic insertion for `phyir insert --path` (command_insert_path.cpp).
#include <filesystem>

#include <glm/glm.hpp>

#include "phyir/insert/insert_object.h"

namespace phyir::cli {

// `steps` placements evenly spaced (in pixels) from `from` to `to`, each written to
// out/frame_NNN/ as `phyir insert` writes one, and out/contact_sheet.png (4 frames a row).
void insert_along_path(const insert::InsertView& view, const scenes::Scene& object, insert::InsertRequest request,
                       glm::ivec2 from, glm::ivec2 to, int steps, const std::filesystem::path& out);

}  // namespace phyir::cli
