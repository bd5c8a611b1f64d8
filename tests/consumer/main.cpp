// Projects a noisy unit sphere onto its PSS through the installed library and checks the
// result against the sphere: exit 0 when every point lands near it.
#include <cmath>
#include <cstdio>
#include <random>

#include "pss/points/project_cloud.hpp"
#include "pss/points/spacing.hpp"

int main() {
  pss::PointCloud cloud;
  std::mt19937 random(7);
  std::normal_distribution<float> gauss;
  for (int i = 0; i < 4000; ++i) {
    const pss::vec3 d = glm::normalize(pss::vec3(gauss(random), gauss(random), gauss(random)));
    cloud.positions.push_back(d * (1.0f + 0.002f * gauss(random)));
  }
  const float h = float(pss::estimate_spacing(cloud.positions).suggested_h);
  pss::ProjectionParams params = pss::ProjectionParams::from_h(h);
  params.support = pss::Support::adaptive;  // as the README's example
  pss::Stats stats;
  const pss::CloudProjection out = pss::project_cloud(cloud, params, pss::Backend::cpu, stats);
  float worst = 0;
  for (const pss::vec3& p : out.cloud.positions) worst = std::fmax(worst, std::fabs(glm::length(p) - 1.0f));
  std::printf("projected %zu points with h = %g: farthest %g from the sphere\n", out.cloud.size(), h, worst);
  return out.cloud.size() == cloud.size() && worst < 0.005f ? 0 : 1;
}
