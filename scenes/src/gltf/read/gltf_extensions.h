#pragma once
// Which glTF extensions the loader understands, and what it does instead for the others.
#include <string>
#include <vector>

namespace phyir::scenes::gltf {

// The extensions the loader implements (a file may require these).
const std::vector<std::string>& supported_extensions();
bool is_supported_extension(const std::string& name);

// For an extension the loader does not implement: the warning that says what happens
// instead, e.g. "KHR_materials_clearcoat ignored: base layer only".
std::string unsupported_extension_warning(const std::string& name);

}  // namespace phyir::scenes::gltf
