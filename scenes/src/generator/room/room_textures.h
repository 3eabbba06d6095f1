#pragma once
// Procedural, seamlessly tiling texture images for the room generator (wood planks,
// checker, tiles, worn metal). Pure functions of the spec: the same spec gives the same
// texels, and so the same PNG bytes.
#include "phyir/core/image.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

// An RGB image of spec.size x spec.size with values in [0,1]: sRGB-encoded colours, or for
// WornMetal the glTF metallicRoughness layout (R unused = 1, G = roughness, B = metalness).
Image render_texture(const TextureSpec& spec);

}  // namespace phyir::scenes
