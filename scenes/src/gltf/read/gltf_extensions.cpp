#include "gltf/read/gltf_extensions.h"

#include <algorithm>
#include <map>

namespace phyir::scenes::gltf {

const std::vector<std::string>& supported_extensions() {
  static const std::vector<std::string> names = {"EXT_mesh_gpu_instancing", "EXT_texture_webp",
                                                 "KHR_lights_punctual", "KHR_materials_emissive_strength",
                                                 "KHR_materials_ior", "KHR_materials_specular",
                                                 "KHR_materials_transmission", "KHR_texture_transform",
                                                 "EXT_meshopt_compression", "KHR_draco_mesh_compression",
                                                 "KHR_mesh_quantization"};
  return names;
}

bool is_supported_extension(const std::string& name) {
  const auto& names = supported_extensions();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string unsupported_extension_warning(const std::string& name) {
  // The fallback is what the core glTF data gives; these say what that means here.
  static const std::map<std::string, std::string> fallbacks = {
      {"KHR_materials_volume",
       "glass treated as a solid refractive dielectric (no thickness, no absorption)"},
      {"KHR_materials_clearcoat", "base layer only"},
      {"KHR_materials_sheen", "base layer only, no sheen"},
      {"KHR_materials_iridescence", "no thin-film interference"},
      {"KHR_materials_anisotropy", "isotropic roughness"},
      {"KHR_materials_dispersion", "one IOR for all wavelengths"},
      {"KHR_materials_unlit", "shaded as a regular PBR material"},
      {"KHR_materials_variants", "the default material mapping"},
      {"KHR_materials_pbrSpecularGlossiness", "the pbrMetallicRoughness fallback values"},
      {"KHR_texture_basisu", "the texture's core image source, if any"},
  };
  const auto it = fallbacks.find(name);
  return name + " ignored: " + (it != fallbacks.end() ? it->second : "not supported, core glTF data used");
}

}  // namespace phyir::scenes::gltf
