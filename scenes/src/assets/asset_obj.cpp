// read_obj: tinyobjloader over a stream from the archive, with a MaterialReader that reads
// the MTL from the same archive.
#include "assets/asset_obj.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <sstream>

#include "assets/asset_zip.h"
#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

std::string lower(std::string text);

std::string trim_warning(const std::string& text) {
  const size_t end = text.find_last_not_of(" \n");
  return end == std::string::npos ? "" : text.substr(0, end + 1);
}

// tinyobjloader's warnings, one per line and often repeated (one per usemtl): each distinct
// line once, with its count.
void add_loader_warnings(const std::string& text, const std::string& obj_path, std::vector<std::string>& warnings) {
  std::vector<std::pair<std::string, int>> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    line = trim_warning(line);
    line.erase(0, line.find_first_not_of(". "));  // tinyobjloader ends some messages with "\n."
    if (line.empty()) continue;
    auto it = std::find_if(lines.begin(), lines.end(), [&](const auto& l) { return l.first == line; });
    if (it == lines.end()) {
      lines.emplace_back(line, 1);
    } else {
      ++it->second;
    }
  }
  for (const auto& [line, count] : lines) {
    warnings.push_back(obj_path + ": " + line + (count > 1 ? " (" + std::to_string(count) + " times)" : ""));
  }
}

// Reads "mtllib NAME" from the archive, relative to the OBJ's folder (case-insensitive as a
// fallback), keeping our parse (MtlMaterial) beside tinyobjloader's names and indices.
class ArchiveMaterialReader : public tinyobj::MaterialReader {
 public:
  ArchiveMaterialReader(const ZipArchive& zip, std::string folder, ObjSoup& soup)
      : zip_(zip), folder_(std::move(folder)), soup_(soup) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* index_of, std::string* warn, std::string* err) override {
    std::optional<std::string> path = zip_.find_ignoring_case(archive_join(folder_, name));
    if (!path) {
      path = only_mtl_in_folder();
      *warn += "MTL file '" + archive_join(folder_, name) + "' is not in the archive" +
               (path ? ": used '" + *path + "', the only MTL beside the OBJ\n" : "\n");
      if (!path) return false;
    }
    const std::vector<unsigned char> bytes = zip_.read(*path);
    for (MtlMaterial& mtl : parse_mtl(std::string(bytes.begin(), bytes.end()), *path, &soup_.warnings)) {
      tinyobj::material_t named{};
      named.name = mtl.name;
      index_of->emplace(mtl.name, static_cast<int>(materials->size()));
      materials->push_back(named);
      soup_.materials.push_back(std::move(mtl));
    }
    soup_.mtl_folder = archive_folder(*path);
    (void)err;
    return true;
  }

 private:
  // Renamed MTL files (mtllib naming a file the archive lacks) are usually the one MTL in
  // the OBJ's folder.
  std::optional<std::string> only_mtl_in_folder() const {
    std::vector<std::string> found;
    for (const std::string& stored : zip_.names()) {
      const bool in_folder = stored.rfind(folder_, 0) == 0 && stored.find('/', folder_.size()) == std::string::npos;
      if (in_folder && stored.size() > 4 && lower(stored.substr(stored.size() - 4)) == ".mtl") found.push_back(stored);
    }
    if (found.size() == 1) return found.front();
    return std::nullopt;
  }

  const ZipArchive& zip_;
  std::string folder_;
  ObjSoup& soup_;
};

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool in_range(int index, size_t size) { return index >= 0 && static_cast<size_t>(index) < size; }

// A corner of tinyobjloader's output, checked against the arrays (-1 where absent); false
// when its position is out of range.
bool checked_corner(const tinyobj::index_t& index, const ObjSoup& soup, ObjCorner& corner) {
  corner.position = index.vertex_index;
  corner.texcoord = in_range(index.texcoord_index, soup.texcoords.size()) ? index.texcoord_index : -1;
  corner.normal = in_range(index.normal_index, soup.normals.size()) ? index.normal_index : -1;
  return in_range(corner.position, soup.positions.size());
}

void copy_arrays(const tinyobj::attrib_t& attrib, ObjSoup& soup) {
  soup.positions.resize(attrib.vertices.size() / 3);
  for (size_t i = 0; i < soup.positions.size(); ++i) {
    soup.positions[i] = {attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
  }
  soup.normals.resize(attrib.normals.size() / 3);
  for (size_t i = 0; i < soup.normals.size(); ++i) {
    soup.normals[i] = {attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]};
  }
  soup.texcoords.resize(attrib.texcoords.size() / 2);
  for (size_t i = 0; i < soup.texcoords.size(); ++i) {
    soup.texcoords[i] = {attrib.texcoords[2 * i], attrib.texcoords[2 * i + 1]};
  }
}

// Faces of every shape as triangles; faces naming no known material get the default one.
void copy_triangles(const std::vector<tinyobj::shape_t>& shapes, int default_material, ObjSoup& soup) {
  size_t dropped = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t count = mesh.num_face_vertices[f];
      ObjTriangle triangle;
      bool valid = count == 3 && offset + 3 <= mesh.indices.size();
      for (size_t k = 0; valid && k < 3; ++k) valid = checked_corner(mesh.indices[offset + k], soup, triangle.corners[k]);
      offset += count;
      if (!valid) {
        ++dropped;
        continue;
      }
      const int material = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      triangle.material = in_range(material, soup.materials.size()) ? material : default_material;
      triangle.smoothing = f < mesh.smoothing_group_ids.size() ? mesh.smoothing_group_ids[f] : 0;
      soup.triangles.push_back(triangle);
    }
  }
  if (dropped > 0) soup.warnings.push_back(std::to_string(dropped) + " faces dropped (fewer than 3 vertices or indices out of range)");
}

MtlMaterial default_material() {
  MtlMaterial m;
  m.name = "(default)";
  m.Kd = glm::vec3(1.0f);  // Java 3D's default material, what Sweet Home 3D shows
  return m;
}

}  // namespace

std::string archive_folder(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string archive_join(const std::string& folder, const std::string& relative) {
  std::string name = relative;
  for (char& c : name) {
    if (c == '\\') c = '/';
  }
  std::vector<std::string> parts;
  std::istringstream in(folder + name);
  for (std::string part; std::getline(in, part, '/');) {
    if (part.empty() || part == ".") continue;
    if (part == ".." && !parts.empty()) {
      parts.pop_back();
    } else if (part != "..") {
      parts.push_back(part);
    }
  }
  std::string joined;
  for (const std::string& part : parts) joined += (joined.empty() ? "" : "/") + part;
  return joined;
}

ObjSoup read_obj(const ZipArchive& zip, const std::string& obj_path) {
  const std::vector<unsigned char> bytes = zip.read(obj_path);
  ObjSoup soup;
  soup.mtl_folder = archive_folder(obj_path);
  std::istringstream in(std::string(bytes.begin(), bytes.end()));
  ArchiveMaterialReader reader(zip, archive_folder(obj_path), soup);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &reader, /*triangulate=*/true)) {
    fail("{}: {}: tinyobjloader cannot read it: {}", zip.path().string(), obj_path, trim_warning(err));
  }
  add_loader_warnings(warn, obj_path, soup.warnings);
  copy_arrays(attrib, soup);
  soup.materials.push_back(default_material());
  copy_triangles(shapes, static_cast<int>(soup.materials.size()) - 1, soup);
  return soup;
}

}  // namespace phyir::scenes
