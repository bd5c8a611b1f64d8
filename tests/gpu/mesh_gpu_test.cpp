// `pss mesh` on the device (issue 27): the same kernels as the CPU, so the same closed,
// oriented surfaces on the analytic truth, of clouds and of volumes. Skips cleanly without a device (CI).
#include <gtest/gtest.h>

#include <cmath>

#include "pss/mesh/mesh_cloud.hpp"
#include "pss/mesh/mesh_volume.hpp"
#include "support/shapes.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

// The GPU's mesh of a torus against the CPU's: closed, one component, χ = 0. Rounding may
// move a corner's sign where the surface passes within ulps of it: the meshes agree in size
// to a fraction of a percent and lie as close to the torus (within `slack`), and the GPU's
// normals are the torus's (cosine above `cosine`).
template <class Torus>
void expect_as_the_cpu(const TriangleMesh& cpu, const TriangleMesh& gpu, const Torus& torus, float slack,
                       float cosine) {
  const MeshTopology t = topology(gpu);
  EXPECT_TRUE(t.watertight());
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.euler_characteristic(), 0);
  EXPECT_NEAR(double(gpu.triangles.size()), double(cpu.triangles.size()), 0.002 * double(cpu.triangles.size()));
  float cpu_worst = 0, gpu_worst = 0;
  for (const vec3& p : cpu.positions) cpu_worst = std::max(cpu_worst, std::abs(torus.distance(p)));
  for (const vec3& p : gpu.positions) gpu_worst = std::max(gpu_worst, std::abs(torus.distance(p)));
  EXPECT_LT(gpu_worst, 1.05f * cpu_worst + slack);
  for (std::size_t i = 0; i < gpu.positions.size(); ++i)
    ASSERT_GT(glm::dot(gpu.normals[i], torus.normal(gpu.positions[i])), cosine) << i;
}

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
    expect_as_the_cpu(cpu.mesh, gpu.mesh, torus, 1e-4f, 0.95f);
  }
}

// A CT-like torus (a logistic step of the distance, noise 2 % of the contrast): the GPU's
// mesh of its iso-surface is the CPU's, closed, on the torus, facing out.
TEST(GpuMesh, AVolumesTorusMeshesAsTheCpuDoes) {
  if (cuda::device_count() == 0) GTEST_SKIP() << "no CUDA device";
  const test::Field torus = test::torus_distance(vec3(21.7f, 21.4f, 11.6f), 13, 5);
  test::SampleVolumeOptions o;
  o.dims = ivec3(44, 44, 24);
  o.noise = 2;
  for (const bool corrector : {false, true}) {
    SCOPED_TRACE(corrector);
    VolumeSettings s;
    s.iso = 50;
    s.method = corrector ? VolumeMethod::predictor_corrector : VolumeMethod::predictor;
    Stats stats;
    const PreparedVolume volume =
        prepare_volume(test::sample_volume(test::smooth_indicator(torus, 100, 0.4f), o), s, stats);
    const VolumeMesh cpu = mesh_volume(volume, 0, Backend::cpu, stats);
    const VolumeMesh gpu = mesh_volume(volume, 0, Backend::cuda, stats);
    expect_as_the_cpu(cpu.mesh, gpu.mesh, torus, 1e-3f, 0.9f);
  }
}

}  // namespace
}  // namespace pss
