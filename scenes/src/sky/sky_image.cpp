// The Preetham sky rendered into the toolkit's equirect mapping.
#include <tbb/parallel_for.h>

#include <cmath>

#include "phyir/core/equirect.h"
#include "phyir/core/error.h"
#include "phyir/scenes/sky.h"

namespace phyir::scenes {

Image sky_image(const PreethamSky& sky, int width) {
  if (width < 8 || width > 65536 || width % 2 != 0) fail("sky: width {} must be even and in [8, 65536]", width);
  const int height = width / 2;
  Image image(width, height, 3);
  // Rows are independent: the same pixels whatever the thread count.
  tbb::parallel_for(0, height, [&](int j) {
    const double theta = 3.14159265358979323846 * (j + 0.5) / height;
    const float cos_theta = static_cast<float>(std::cos(theta)), sin_theta = static_cast<float>(std::sin(theta));
    for (int i = 0; i < width; ++i) {
      const glm::vec3 d = equirect_direction((i + 0.5f) / width, cos_theta, sin_theta);
      const glm::dvec3 L = sky.radiance(glm::normalize(glm::dvec3(d)));
      for (int c = 0; c < 3; ++c) image.at(i, j, c) = static_cast<float>(L[c]);
    }
  });
  return image;
}

}  // namespace phyir::scenes
