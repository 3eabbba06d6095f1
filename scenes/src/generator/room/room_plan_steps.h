#pragma once
// The steps plan_room() runs, one source file each.
#include "generator/room/room_rng.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::scenes {

// room_shell.cpp: size, height and (hard only) the L-shape notch.
RoomShell plan_shell(Pcg32& rng, RoomPreset preset);

// room_viewpoints.cpp: picks the camera and the candidate viewpoints among valid points.
// Returns false when fewer than 1 + kMinCandidateViewpoints valid, spread-out points exist.
bool plan_viewpoints(RoomLayout& layout, Pcg32 rng);

// room_plan.cpp helpers: drops materials no part or surface uses (a piece that did not fit
// may have created one), then textures no material uses, renumbering the references.
void prune_unused_materials(RoomLayout& layout);

}  // namespace phyir::scenes
