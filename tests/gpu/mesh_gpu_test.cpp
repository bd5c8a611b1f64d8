// `pss mesh` on the device (issue 27): the same kernels as the CPU, so the same closed,
// oriented surfaces on the analytic truth. Skips cleanly without a device (CI).
#include <gtest/gtest.h>

#include <cmath>

#include "pss/mesh/mesh_cloud.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

TEST(GpuMesh, EverySurfaceMeshesTheTorusAsTheCpuDoes) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  test::SampleOptions o;
  o.count = 20000;
  const test::Torus torus{1.0f, 0.35f};
  const PointCloud cloud = test::sample(torus, o);
  for (const SurfaceOperator surface : {SurfaceOperator::mls, SurfaceOperator::apss, SurfaceOperator::rimls}) {
    SCOPED_TRACE(surface_name(surface));
    MeshParams params;
    params.projection = ProjectionParams::from_h(test::suggested_h(cloud));
    params.projection.support = Support::adaptive;
    params.projection.surface = surface;
    params.projection.borders = BorderMode::clip;
    Stats stats;
    const CloudMesh cpu = mesh_cloud(cloud, params, Backend::cpu, stats);
    const CloudMesh gpu = mesh_cloud(cloud, params, Backend::cuda, stats);
    const MeshTopology t = topology(gpu.mesh);
    EXPECT_TRUE(t.watertight());
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.euler_characteristic(), 0);
    // Rounding may move a corner's sign where the surface passes within ulps of it: the
    // meshes agree in size to a fraction of a percent, and lie as close to the torus.
    EXPECT_NEAR(double(gpu.mesh.triangles.size()), double(cpu.mesh.triangles.size()),
                0.002 * double(cpu.mesh.triangles.size()));
    float cpu_worst = 0, gpu_worst = 0;
    for (const vec3& p : cpu.mesh.positions) cpu_worst = std::max(cpu_worst, std::abs(torus.distance(p)));
    for (const vec3& p : gpu.mesh.positions) gpu_worst = std::max(gpu_worst, std::abs(torus.distance(p)));
    EXPECT_LT(gpu_worst, 1.05f * cpu_worst + 1e-4f);
    for (std::size_t i = 0; i < gpu.mesh.positions.size(); ++i)
      ASSERT_GT(glm::dot(gpu.mesh.normals[i], torus.normal(gpu.mesh.positions[i])), 0.95f) << i;
  }
}

}  // namespace
}  // namespace pss
