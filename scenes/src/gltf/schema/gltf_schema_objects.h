#pragma once
// One check per object type of the glTF 2.0 schema (gltf_schema_data.cpp, _scene.cpp,
// _materials.cpp) and the extensions they may carry (gltf_schema_extensions.cpp). Each takes
// the object and its properties; references between objects are checked later, by the loader.
#include "gltf/schema/gltf_schema_rules.h"

namespace phyir::scenes::gltf::schema {

// Buffers and accessors.
void check_buffer(const Object& buffer);
void check_buffer_view(const Object& view);
void check_accessor(const Object& accessor);

// The node tree and what hangs on it.
void check_scene(const Object& scene);
void check_node(const Object& node);
void check_mesh(const Object& mesh);
void check_camera(const Object& camera);
void check_skin(const Object& skin);
void check_animation(const Object& animation);

// Materials and textures.
void check_material(const Object& material);
void check_texture_info(const Object& info);
void check_texture(const Object& texture);
void check_sampler(const Object& sampler);
void check_image(const Object& image);

// The extensions each object type may carry, checked when present.
void check_root_extensions(const Object& gltf);
void check_node_extensions(const Object& node);
void check_primitive_extensions(const Object& primitive);
void check_buffer_extensions(const Object& buffer);
void check_buffer_view_extensions(const Object& view);
void check_material_extensions(const Object& material);
void check_texture_info_extensions(const Object& info);
void check_texture_extensions(const Object& texture);

}  // namespace phyir::scenes::gltf::schema
