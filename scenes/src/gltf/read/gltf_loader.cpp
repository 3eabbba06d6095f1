// load_gltf: the stages in order. Each stage lives in its own gltf_*.cpp.
#include "phyir/scenes/gltf_loader.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <map>
#include <optional>

#include "gltf/read/gltf_cameras.h"
#include "gltf/read/gltf_environment.h"
#include "gltf/read/gltf_portals.h"
#include "gltf/read/gltf_extensions.h"
#include "gltf/read/gltf_file.h"
#include "gltf/read/gltf_geometry.h"
#include "gltf/read/gltf_instancing.h"
#include "gltf/read/gltf_lights.h"
#include "gltf/read/gltf_materials.h"
#include "gltf/read/gltf_nodes.h"
#include "gltf/read/gltf_parse.h"
#include "gltf/read/gltf_preflight.h"
#include "gltf/read/gltf_primitives.h"
#include "gltf/read/gltf_textures.h"
#include "gltf/read/gltf_values.h"

namespace phyir::scenes {

namespace {

using namespace gltf;

void warn_about_unsupported(const GltfContext& ctx) {
  for (const std::string& name : ctx.model.extensionsUsed)
    if (!is_supported_extension(name)) ctx.warn("{}", unsupported_extension_warning(name));
  if (!ctx.model.animations.empty())
    ctx.warn("{} animations ignored: the static pose is used", ctx.model.animations.size());
  if (!ctx.model.skins.empty())
    ctx.warn("{} skins ignored: skinned meshes keep their bind pose", ctx.model.skins.size());
}

// scenes[scene].extras.phyir.candidate_viewpoints: [[x, y, z], ...], written by the room
// generator. Absent is fine; malformed entries are skipped with a warning.
std::vector<glm::vec3> read_candidate_viewpoints(const GltfContext& ctx, int scene) {
  if (scene < 0) return {};
  const tinygltf::Value* phyir = member(ctx.model.scenes[static_cast<size_t>(scene)].extras, "phyir");
  const tinygltf::Value* list = phyir != nullptr ? member(*phyir, "candidate_viewpoints") : nullptr;
  if (list == nullptr) return {};
  const std::string where = fmt::format("scene {} extras.phyir.candidate_viewpoints", scene);
  if (!list->IsArray()) {
    ctx.warn("{} is not an array: ignored", where);
    return {};
  }
  std::vector<glm::vec3> viewpoints;
  for (size_t i = 0; i < list->ArrayLen(); ++i) {
    const auto p = as_vec3(list->Get(static_cast<int>(i)));
    if (p)
      viewpoints.push_back(*p);
    else
      ctx.warn("{} entry {} is not [x, y, z]: skipped", where, i);
  }
  return viewpoints;
}

// What InstanceBaker drew, for SourceInfo.
struct BakeCounts {
  int mesh_instances = 0;       // nodes with a mesh
  int gpu_instances = 0;        // EXT_mesh_gpu_instancing copies
  size_t unique_triangles = 0;  // each primitive drawn counted once
};

SourceInfo source_info(const tinygltf::Model& model, int default_scene, const BakeCounts& counts) {
  SourceInfo info;
  info.nodes = static_cast<int>(model.nodes.size());
  info.meshes = static_cast<int>(model.meshes.size());
  for (const tinygltf::Mesh& mesh : model.meshes) info.primitives += static_cast<int>(mesh.primitives.size());
  info.mesh_instances = counts.mesh_instances;
  info.gpu_instances = counts.gpu_instances;
  info.unique_triangles = counts.unique_triangles;
  info.materials = static_cast<int>(model.materials.size());
  info.textures = static_cast<int>(model.textures.size());
  info.images = static_cast<int>(model.images.size());
  info.samplers = static_cast<int>(model.samplers.size());
  info.cameras = static_cast<int>(model.cameras.size());
  info.lights = static_cast<int>(model.lights.size());
  info.default_scene = default_scene;
  info.extensions_used = model.extensionsUsed;
  info.extensions_required = model.extensionsRequired;
  info.generator = model.asset.generator;
  return info;
}

// Baking copies every GPU instance (the renderer takes world-space meshes), so what
// instancing may add is bounded: an instancing accessor without a bufferView is up to 2^24
// zeros in a few bytes of JSON. 2^25 vertices is about 1.2 GB baked with normals, tangents
// and UVs; beyond that a scene needs instancing in the renderer.
constexpr size_t kMaxInstancedVertices = size_t{1} << 25;

// Adds the meshes and cameras of the flattened node tree to the scene. Each primitive is
// read once however many nodes (or GPU instances) draw its mesh.
class InstanceBaker {
 public:
  InstanceBaker(const GltfContext& ctx, Scene& scene) : ctx_(ctx), scene_(scene) {}

  BakeCounts add(const std::vector<NodeInstance>& instances) {
    for (const NodeInstance& instance : instances) {
      const tinygltf::Node& node = ctx_.model.nodes[static_cast<size_t>(instance.node)];
      const std::optional<InstanceAttributes> gpu = find_gpu_instancing(ctx_, instance.node);
      if (node.mesh >= 0) {
        add_mesh(node.mesh, instance, gpu);
        ++counts_.mesh_instances;
      }
      if (node.camera >= 0) scene_.cameras.push_back(make_camera(ctx_, instance));
    }
    return counts_;
  }

 private:
  void add_mesh(int mesh_index, const NodeInstance& instance, const std::optional<InstanceAttributes>& gpu) {
    if (!in_range(mesh_index, ctx_.model.meshes.size()))
      ctx_.fail("{} refers to mesh {}, which does not exist ({} meshes)",
                label("node", instance.node, ctx_.model.nodes), mesh_index, ctx_.model.meshes.size());
    if (gpu)
      add_gpu_instances(mesh_index, instance, *gpu);
    else
      add_primitives(mesh_index, instance, nullptr);
  }

  void add_gpu_instances(int mesh_index, const NodeInstance& instance, const InstanceAttributes& gpu) {
    const size_t per_copy = baked_vertices(mesh_index);
    if (per_copy == 0) return;  // nothing to draw: the instances are not even read
    if (gpu.count > (kMaxInstancedVertices - instanced_vertices_) / per_copy)
      ctx_.fail("{} EXT_mesh_gpu_instancing draws {} instances of {} ({} vertices each): more than the {} "
                "vertices instancing may add to a scene once baked ({} already)",
                label("node", instance.node, ctx_.model.nodes), gpu.count,
                label("mesh", mesh_index, ctx_.model.meshes), per_copy, kMaxInstancedVertices, instanced_vertices_);
    instanced_vertices_ += gpu.count * per_copy;
    counts_.gpu_instances += static_cast<int>(gpu.count);
    const InstanceTransforms transforms(ctx_, instance, gpu);
    add_primitives(mesh_index, instance, &transforms);
  }

  // Without `gpu`, one copy placed by the node.
  void add_primitives(int mesh_index, const NodeInstance& instance, const InstanceTransforms* gpu) {
    const tinygltf::Mesh& source = ctx_.model.meshes[static_cast<size_t>(mesh_index)];
    for (size_t p = 0; p < source.primitives.size(); ++p) {
      const std::optional<PrimitiveData>& data = primitive(mesh_index, static_cast<int>(p));
      if (!data) continue;
      Mesh mesh = gpu != nullptr ? bake_instances(*data, *gpu) : bake_to_world(*data, instance.world);
      check_finite_positions(mesh, mesh_index, static_cast<int>(p), instance.node);
      mesh.name =
          fmt::format("{}/{}", source.name.empty() ? fmt::format("mesh{}", mesh_index) : source.name, p);
      mesh.material = material_index(source.primitives[p].material, mesh_index, static_cast<int>(p));
      add_tangents_for_normal_map(mesh, mesh_index, static_cast<int>(p));
      scene_.meshes.push_back(std::move(mesh));
    }
  }

  // Finite file positions can still overflow floats once transformed (scale 1e300).
  void check_finite_positions(const Mesh& mesh, int mesh_index, int primitive, int node) const {
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::vec3& v = mesh.positions[i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        ctx_.fail("{} placed by {} has vertex {} at ({}, {}, {}): the node transforms overflow 32-bit floats",
                  primitive_label(ctx_, mesh_index, primitive), label("node", node, ctx_.model.nodes), i, v.x, v.y,
                  v.z);
    }
  }

  const std::optional<PrimitiveData>& primitive(int mesh, int primitive) {
    const auto key = std::make_pair(mesh, primitive);
    auto found = primitives_.find(key);
    if (found == primitives_.end()) {
      found = primitives_.emplace(key, read_primitive(ctx_, mesh, primitive)).first;
      if (found->second) counts_.unique_triangles += found->second->triangles.size();
    }
    return found->second;
  }

  // Vertices one copy of the mesh bakes to (bake_to_world unshares them for flat normals).
  size_t baked_vertices(int mesh_index) {
    size_t vertices = 0;
    const size_t primitives = ctx_.model.meshes[static_cast<size_t>(mesh_index)].primitives.size();
    for (size_t p = 0; p < primitives; ++p) {
      const std::optional<PrimitiveData>& data = primitive(mesh_index, static_cast<int>(p));
      if (data) vertices += data->normals.empty() ? 3 * data->triangles.size() : data->positions.size();
    }
    return vertices;
  }

  int material_index(int material, int mesh, int primitive) {
    const int file_materials = static_cast<int>(ctx_.model.materials.size());
    if (material >= file_materials)
      ctx_.fail("{} refers to material {}, which does not exist ({} materials)",
                primitive_label(ctx_, mesh, primitive), material, file_materials);
    if (material >= 0) return material;
    if (default_material_ < 0) {
      default_material_ = static_cast<int>(scene_.materials.size());
      scene_.materials.push_back(default_material());
    }
    return default_material_;
  }

  // glTF asks clients to compute tangents a normal map needs when the file has none.
  void add_tangents_for_normal_map(Mesh& mesh, int mesh_index, int primitive) {
    const Material& material = scene_.materials[static_cast<size_t>(mesh.material)];
    if (!material.normal_texture.present() || !mesh.tangents.empty()) return;
    if (!generate_tangents(mesh, material.normal_texture.texcoord))
      ctx_.warn("{} has a normal map but no TEXCOORD_{}: the normal map has no effect",
                primitive_label(ctx_, mesh_index, primitive), material.normal_texture.texcoord);
  }

  const GltfContext& ctx_;
  Scene& scene_;
  std::map<std::pair<int, int>, std::optional<PrimitiveData>> primitives_;
  int default_material_ = -1;
  BakeCounts counts_;
  size_t instanced_vertices_ = 0;  // baked by GPU instances so far, within kMaxInstancedVertices
};

}  // namespace

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) {
  Scene scene;
  scene.source = path.string();
  const Diagnostics diagnostics(scene.source, scene.warnings);
  const GltfFile file = read_gltf_file(path, diagnostics);
  preflight_check(file, diagnostics);
  const tinygltf::Model model = parse_gltf(file, diagnostics);
  const GltfContext ctx(diagnostics, model);
  warn_about_unsupported(ctx);

  const int default_scene = default_scene_index(ctx);
  const std::vector<NodeInstance> instances = flatten_nodes(ctx, scene_roots(ctx, default_scene));
  TextureTable textures(ctx, scene.textures, options.load_textures);
  scene.materials = convert_materials(ctx, textures);
  textures.decode_all();
  const BakeCounts counts = InstanceBaker(ctx, scene).add(instances);
  scene.lights = read_lights(ctx, instances);
  scene.candidate_viewpoints = read_candidate_viewpoints(ctx, default_scene);
  scene.environment = read_environment(ctx, default_scene, path);
  scene.portals = read_portals(ctx, default_scene);
  scene.info = source_info(model, default_scene, counts);
  scene.bounds = scene.compute_bounds();
  // Camera hits filter textures to their footprint; each pyramid is independent of the others.
  tbb::parallel_for(size_t(0), scene.textures.size(), [&](size_t i) { scene.textures[i].build_mips(); });
  return scene;
}

}  // namespace phyir::scenes
