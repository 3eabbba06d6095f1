// parse_mtl: tinyobjloader reads the values; a scan of the statements says which were
// written (tinyobjloader fills defaults) and keeps texture arguments whole.
#include <tiny_obj_loader.h>

#include <cstdlib>
#include <map>
#include <sstream>

#include "phyir/scenes/asset_material.h"

namespace phyir::scenes {

namespace {

// The statements written under one newmtl: keyword -> the rest of the line, trimmed.
struct WrittenStatements {
  std::string name;
  std::map<std::string, std::string> values;
  bool used = false;
};

std::string trim(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r\n") - begin + 1);
}

// Tokenised as tinyobjloader does: a keyword ends at a space or tab; the name of newmtl is
// the rest of the line.
std::vector<WrittenStatements> scan_statements(std::string_view text) {
  std::vector<WrittenStatements> materials;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) {
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    const size_t space = line.find_first_of(" \t");
    const std::string keyword = line.substr(0, space);
    const std::string rest = space == std::string::npos ? "" : trim(line.substr(space + 1));
    if (keyword == "newmtl") {
      materials.push_back({rest, {}, false});
    } else if (!materials.empty()) {
      materials.back().values[keyword] = rest;
    }
  }
  return materials;
}

WrittenStatements* find_unused(std::vector<WrittenStatements>& scanned, const std::string& name) {
  for (WrittenStatements& s : scanned) {
    if (!s.used && trim(s.name) == trim(name)) return &s;
  }
  return nullptr;
}

glm::vec3 vec3(const tinyobj::real_t* v) { return {v[0], v[1], v[2]}; }

MtlMaterial combine(const tinyobj::material_t& parsed, const WrittenStatements& written) {
  const auto has = [&](const char* keyword) { return written.values.count(keyword) > 0; };
  MtlMaterial m;
  m.name = parsed.name;
  if (has("Kd")) m.Kd = vec3(parsed.diffuse);
  if (has("Ks")) m.Ks = vec3(parsed.specular);
  if (has("Ke")) m.Ke = vec3(parsed.emission);
  if (has("Ns")) m.Ns = parsed.shininess;
  if (has("d")) m.d = parsed.dissolve;
  if (has("Tr")) m.Tr = std::strtof(written.values.at("Tr").c_str(), nullptr);
  if (has("Ni")) m.Ni = parsed.ior;
  if (has("Pr")) m.Pr = parsed.roughness;
  if (has("Pm")) m.Pm = parsed.metallic;
  if (has("illum")) m.illum = parsed.illum;
  m.map_Kd = parsed.diffuse_texname;
  if (has("map_Kd")) m.map_Kd_raw = written.values.at("map_Kd");
  m.map_d = parsed.alpha_texname;
  if (has("map_d")) m.map_d_raw = written.values.at("map_d");
  return m;
}

}  // namespace

std::vector<MtlMaterial> parse_mtl(std::string_view text, const std::string& source,
                                   std::vector<std::string>* warnings) {
  std::vector<tinyobj::material_t> parsed;
  std::map<std::string, int> index_of;
  std::string warn, err;
  std::istringstream in{std::string(text)};
  tinyobj::LoadMtl(&index_of, &parsed, &in, &warn, &err);
  if (warnings && !warn.empty()) warnings->push_back(source + ": " + trim(warn));
  std::vector<WrittenStatements> scanned = scan_statements(text);
  std::vector<MtlMaterial> materials;
  for (const tinyobj::material_t& material : parsed) {
    WrittenStatements* written = find_unused(scanned, material.name);
    if (!written) continue;  // tinyobjloader's default material when no newmtl precedes
    written->used = true;
    materials.push_back(combine(material, *written));
  }
  return materials;
}

}  // namespace phyir::scenes
