#pragma once
// What a training path tells the guide (path guiding, docs/guiding.md): at each vertex whose
// next direction came from a density, the radiance that arrived along it, as a record for the
// SD-tree. The radiance is everything the path gathers after the vertex divided by the
// throughput beyond it (componentwise), as the estimate weighs it: an emitter or the sky
// hit by the vertex's own ray counts with its MIS weight, the share next-event estimation
// leaves to the sampled direction, so the guide learns what that direction is responsible
// for and does not chase lights that light sampling already finds. Private to the path tracer.
#include <glm/glm.hpp>

#include "phyir/core/safe_math.h"
#include "phyir/render/guiding/radiance_record.h"

namespace phyir::render {

class PathRecords {
 public:
  explicit PathRecords(guiding::RecordBuffer* out) : out_(out) {}

  // A vertex at `position` whose next ray goes along `direction` (world), drawn with density
  // `pdf`; `beta` is the path's throughput beyond it.
  void add_vertex(const glm::vec3& position, const glm::vec3& direction, float pdf, const glm::vec3& beta) {
    if (count_ == kMaxVertices) return;  // deeper vertices are not recorded: they carry little light
    const glm::vec3 inv_beta(safe_div(1.0f, beta.x), safe_div(1.0f, beta.y), safe_div(1.0f, beta.z));
    vertices_[count_++] = Vertex{position, direction, inv_beta, glm::vec3(0.0f), pdf};
  }
  // Light the estimate gathered (throughput and MIS weight included).
  void gather(const glm::vec3& light) {
    for (int i = 0; i < count_; ++i) vertices_[i].radiance += light * vertices_[i].inv_beta;
  }

  // Appends one record per vertex (the SD-tree drops non-finite ones and counts them).
  void flush() {
    for (int i = 0; i < count_; ++i) {
      const Vertex& v = vertices_[i];
      out_->push_back(guiding::RadianceRecord{v.position, v.direction, luminance(v.radiance), v.pdf});
    }
    count_ = 0;
  }

 private:
  // Paths end after max_bounces (8 by default); 16 records cover every usual setting.
  static constexpr int kMaxVertices = 16;
  struct Vertex {
    glm::vec3 position, direction, inv_beta, radiance;
    float pdf;
  };
  guiding::RecordBuffer* out_;
  Vertex vertices_[kMaxVertices];
  int count_ = 0;
};

}  // namespace phyir::render
