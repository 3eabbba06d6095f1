#pragma once
// The files the glTF writer puts beside the .gltf (images, the environment map): their
// URIs, their type and their copying.
#include <filesystem>
#include <string>

#include "phyir/scenes/gltf_writer.h"

namespace phyir::scenes::gltf_write {

// Refuses a URI that is not a plain relative path: components of letters, digits, '.', '_'
// and '-' separated by '/', none of them "." or "..". Such a URI needs no percent-encoding
// and stays inside the .gltf's folder. `what` names its owner in the message.
void check_side_uri(const std::string& uri, const std::string& what);

// "image/png" or "image/jpeg" from the source's first bytes; fails when they are neither, or
// when the uri's extension names the other type (.png; .jpg or .jpeg).
std::string image_mime_type(const GltfFileSource& source, const std::string& uri, const std::string& what);

// Fails unless the source is readable: its file exists (or it has bytes).
void check_source(const GltfFileSource& source, const std::string& what);

bool same_source(const GltfFileSource& a, const GltfFileSource& b);

// Writes `file` into `dir` atomically, creating its folders; nothing when the source file
// already is that file.
void write_side_file(const std::filesystem::path& dir, const GltfSideFile& file);

}  // namespace phyir::scenes::gltf_write
