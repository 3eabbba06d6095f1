#pragma once
// What a training path tells the guide (path guiding, docs/guiding.md): at each vertex whose
// next direction came from a density, the radiance that arrived along it, as a record for the
// SD-tree. The radiance is everything the path gathers after the vertex divided by the
// throughput beyond it (componentwise), with one exception: the emitter or sky that the
// vertex's own ray hits counts in full, not MIS-weighted, since the guide learns the incident
// radiance, not one strategy's share of it. Private to the path tracer.
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
    ray_from_last_ = count_ < kMaxVertices;
    if (!ray_from_last_) return;  // deeper vertices are not recorded: they carry little light
    const glm::vec3 inv_beta(safe_div(1.0f, beta.x), safe_div(1.0f, beta.y), safe_div(1.0f, beta.z));
    vertices_[count_++] = Vertex{position, direction, inv_beta, glm::vec3(0.0f), pdf};
  }
  // The current ray did not come from the last vertex (a delta bounce came between).
  void leave_last_vertex() { ray_from_last_ = false; }

  // Light the estimate gathered (`weighted`, throughput included); `unweighted` is the same
  // without its MIS weight, for the vertex whose own ray found it.
  void gather(const glm::vec3& weighted, const glm::vec3& unweighted) {
    for (int i = 0; i < count_; ++i) {
      const bool own = ray_from_last_ && i == count_ - 1;
      vertices_[i].radiance += (own ? unweighted : weighted) * vertices_[i].inv_beta;
    }
  }
  void gather(const glm::vec3& weighted) { gather(weighted, weighted); }

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
  bool ray_from_last_ = false;
};

}  // namespace phyir::render
