#pragma once
// Integer vertex attributes: which component types each attribute may use (the core spec's
// normalized unsigned texcoords and colours, and KHR_mesh_quantization's wider set), and
// the rule that turns a stored integer into a float. Quantized positions come with a node
// transform that scales them back; the loader bakes node transforms, so nothing else is
// needed here.
#include <string>
#include <vector>

namespace phyir::scenes::gltf {

struct ComponentKind {
  int component_type;  // TINYGLTF_COMPONENT_TYPE_*
  bool normalized;
};

// What a use of an accessor accepts: accessor types (TINYGLTF_TYPE_*), and the integer
// component kinds that may stand in for FLOAT, by the core spec or by KHR_mesh_quantization.
struct FloatFormat {
  std::vector<int> types;
  std::vector<ComponentKind> core;
  std::vector<ComponentKind> quantized;
};

// The format of the vertex attribute `name`: POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n.
// Other names get an empty format (no types): the loader does not read them.
FloatFormat attribute_format(const std::string& name);

enum class KindUse { float_data, core, quantized, refused };
KindUse classify(const FloatFormat& format, const ComponentKind& kind);

// One stored component as a float (glTF 2.0 section 3.11, KHR_mesh_quantization): FLOAT as
// stored; normalized unsigned c / (2^n - 1); normalized signed max(c / (2^(n-1) - 1), -1);
// a non-normalized integer keeps its value. `component` holds at least component_size bytes.
float dequantize(const unsigned char* component, int component_type, bool normalized);

// Bytes of one component, 0 for a type glTF 2.0 accessors cannot have.
size_t component_size(int component_type);
const char* component_name(int component_type);

// "SHORT (normalized) or UNSIGNED_BYTE": the kinds for messages.
std::string describe_kinds(const std::vector<ComponentKind>& kinds);

}  // namespace phyir::scenes::gltf
