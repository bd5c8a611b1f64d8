// Sharp creases in a mesh (issue 27: "with --surface rimls, sharp creases kept"): a box's
// exact signed distance, turned against the lattice, meshed with and without the creases'
// vertices (src/mesh/creases.hpp), against its edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/common.hpp>

#include <fstream>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "support/analytic_implicit.hpp"
#include "support/cli.hpp"
#include "support/iso_reference.hpp"
#include "support/mesh_readers.hpp"
#include "support/mesh_checks.hpp"
#include "support/self_intersection.hpp"
#include "support/shapes.hpp"

namespace pss {
namespace {

// A box centred at the origin with half-sides `half`, turned by `turn`: creases of 90°
// along its twelve edges.
struct TurnedBox {
  glm::mat3 turn;
  vec3 half;
  float distance(vec3 p) const {
    const vec3 q = glm::abs(glm::transpose(turn) * p) - half;
    return glm::length(glm::max(q, 0.0f)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
  }
  vec3 normal(vec3 p) const {
    const vec3 local = glm::transpose(turn) * p;
    const vec3 q = glm::abs(local) - half;
    vec3 g(0.0f);
    if (glm::any(glm::greaterThan(q, vec3(0.0f)))) {
      g = glm::max(q, 0.0f) * glm::sign(local);
    } else {
      const int axis = q.x >= q.y && q.x >= q.z ? 0 : q.y >= q.z ? 1 : 2;
      g[axis] = local[axis] < 0 ? -1.0f : 1.0f;
    }
    return turn * glm::normalize(g);
  }
  // Points along the edges, `keep` from the corners.
  std::vector<vec3> edge_points(float keep, int per_edge) const {
    std::vector<vec3> out;
    for (int axis = 0; axis < 3; ++axis)
      for (int corner = 0; corner < 4; ++corner)
        for (int i = 0; i < per_edge; ++i) {
          vec3 local;
          local[axis] = -half[axis] + keep + (2 * half[axis] - 2 * keep) * float(i) / float(per_edge - 1);
          local[(axis + 1) % 3] = (corner & 1 ? 1.0f : -1.0f) * half[(axis + 1) % 3];
          local[(axis + 2) % 3] = (corner & 2 ? 1.0f : -1.0f) * half[(axis + 2) % 3];
          out.push_back(turn * local);
        }
    return out;
  }
};

TurnedBox turned_box() {
  glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.5f, glm::normalize(vec3(1.0f, 2.0f, 0.7f)));
  return {glm::mat3(turn), vec3(0.5f, 0.4f, 0.3f)};
}

// How far the edges' points lie from the mesh, in cubes.
std::vector<float> edge_distances(const TurnedBox& box, const TriangleMesh& m, float cell) {
  std::vector<test::Triangle> triangles;
  for (const auto& t : m.triangles) {
    const auto at = [&](int k) { return m.positions[std::size_t(t[std::size_t(k)])]; };
    triangles.push_back({at(0), at(1), at(2)});
  }
  const test::ReferenceMesh reference(triangles, cell);
  std::vector<float> out;
  for (const vec3& p : box.edge_points(2 * cell, 50)) out.push_back(reference.distance(p) / cell);
  return out;
}

double mean(const std::vector<float>& x) { return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size()); }
double share_within(const std::vector<float>& x, float most) {
  return double(std::count_if(x.begin(), x.end(), [&](float d) { return d <= most; })) / double(x.size());
}

TEST(MeshCreases, ABoxKeepsItsEdges) {
  const TurnedBox box = turned_box();
  const ImplicitSurface s =
      test::analytic([&](vec3 p) { return box.distance(p); }, [&](vec3 p) { return box.normal(p); });
  const vec3 seed[] = {box.turn * vec3(0, 0, 0.3f)};
  const float cell = 0.04f;
  MarchCounts kept, cut;
  const TriangleMesh creased = test::march(s, vec3(-0.8f), vec3(0.8f), cell, seed, kept);
  const TriangleMesh chamfered = test::march(s, vec3(-0.8f), vec3(0.8f), cell, seed, cut, 180);
  EXPECT_EQ(cut.crease_vertices, 0);
  EXPECT_GT(kept.crease_vertices, 0);
  EXPECT_GT(kept.crease_flips, 0);
  for (const TriangleMesh* m : {&creased, &chamfered}) {
    test::expect_one_closed_surface(*m, 2);
    EXPECT_EQ(test::crossing_triangle_pairs(*m), 0);
    for (const vec3& p : m->positions) EXPECT_NEAR(box.distance(p), 0.0f, 1e-4f);
  }
  // Marching alone cuts the edges off by about a fifth of a cube; with the creases' vertices
  // most of them lie on the mesh. The rest pass within a cube of a face's edge, where the
  // cube beside it holds both faces but not the crease.
  const std::vector<float> with = edge_distances(box, creased, cell), without = edge_distances(box, chamfered, cell);
  std::printf("the edges' mean distance to the mesh: %.4f cubes with its creases, %.4f without; within 0.1 cube: "
              "%.0f %%, %.0f %%\n",
              mean(with), mean(without), 100 * share_within(with, 0.1f), 100 * share_within(without, 0.1f));
  EXPECT_GT(mean(without), 0.15);
  EXPECT_LT(mean(with), 0.25 * mean(without));
  EXPECT_GT(share_within(with, 0.1f), 0.8);
  EXPECT_LT(share_within(without, 0.1f), 0.3);
  EXPECT_LT(*std::max_element(with.begin(), with.end()), 0.5f);
}

// The box's faces sampled at random, `count` points with their exact normals, as text
// (x y z nx ny nz).
std::string box_samples(const TurnedBox& box, int count) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const vec3 h = box.half;
  const float areas[3] = {h.y * h.z, h.x * h.z, h.x * h.y};  // of the faces across x, y, z
  const float total = 2 * (areas[0] + areas[1] + areas[2]);
  std::string text;
  char line[160];
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f})
      for (int i = 0; i < int(float(count) * areas[axis] / total); ++i) {
        vec3 local(unit(random), unit(random), unit(random));
        local *= h;
        local[axis] = side * h[axis];
        vec3 normal(0.0f);
        normal[axis] = side;
        const vec3 p = box.turn * local, n = box.turn * normal;
        std::snprintf(line, sizeof line, "%.7g %.7g %.7g %.7g %.7g %.7g\n", double(p.x), double(p.y), double(p.z),
                      double(n.x), double(n.y), double(n.z));
        text += line;
      }
  return text;
}

// Two planes meeting at 160° (their normals 20° apart): a crease the default angle leaves to
// the march, and a smaller one keeps.
TEST(MeshCreases, ACreaseGentlerThanTheAngleIsLeftToTheMarch) {
  const glm::mat3 turn = turned_box().turn;
  const float tilt = 10 * float(M_PI) / 180;
  const vec3 a = turn * vec3(std::sin(tilt), 0, std::cos(tilt)), b = turn * vec3(-std::sin(tilt), 0, std::cos(tilt));
  const ImplicitSurface s = test::analytic([&](vec3 p) { return std::max(glm::dot(a, p), glm::dot(b, p)); },
                                           [&](vec3 p) { return glm::dot(a, p) >= glm::dot(b, p) ? a : b; });
  const vec3 seed[] = {vec3(0.0f)};
  MarchCounts gentle, sharp;
  const TriangleMesh left = test::march(s, vec3(-0.3f), vec3(0.3f), 0.04f, seed, gentle);
  const TriangleMesh kept = test::march(s, vec3(-0.3f), vec3(0.3f), 0.04f, seed, sharp, 10);
  EXPECT_EQ(gentle.crease_vertices, 0);
  EXPECT_GT(sharp.crease_vertices, 5);
  for (const TriangleMesh* m : {&left, &kept}) {
    EXPECT_TRUE(topology(*m).manifold());
    for (const vec3& p : m->positions) EXPECT_NEAR(std::max(glm::dot(a, p), glm::dot(b, p)), 0.0f, 1e-5f);
  }
}

// Normals a little off the faces' (as a fit's are) put the planes' meeting point off the
// surface; the crease's vertex is moved onto it, as every vertex is.
TEST(MeshCreases, ACreasesVertexIsMovedOntoTheSurface) {
  const TurnedBox box = turned_box();
  const vec3 lean = glm::normalize(vec3(1.0f, -2.0f, 0.5f));
  const ImplicitSurface s = test::analytic([&](vec3 p) { return box.distance(p); },
                                           [&](vec3 p) { return glm::normalize(box.normal(p) + 0.04f * lean); });
  const vec3 seed[] = {box.turn * vec3(0, 0, 0.3f)};
  MarchCounts counts;
  const TriangleMesh m = test::march(s, vec3(-0.8f), vec3(0.8f), 0.04f, seed, counts);
  EXPECT_GT(counts.crease_vertices, 50);
  test::expect_one_closed_surface(m, 2);
  // Every vertex on the surface to the roots' precision, but for the few whose point on it
  // lies outside their cube: those within the tolerance of a crease's (0.02 cube).
  int off = 0;
  for (const vec3& p : m.positions) {
    EXPECT_NEAR(box.distance(p), 0.0f, 0.02f * 0.04f);
    off += std::abs(box.distance(p)) > 1e-5f;
  }
  EXPECT_LT(off, counts.crease_vertices / 4);
}

// A sphere whose normals are noisy (about 11° each, as a scan's fits may be): they differ by
// more than the crease angle within many cubes, but their planes rarely meet on one point
// (without the test of their residual, 14 % of the cubes got a fan; with it, 1.5 %).
TEST(MeshCreases, NoisyNormalsOfASmoothSurfaceMakeNoCrease) {
  const test::Sphere sphere;
  const auto noise = [](vec3 p) {  // a fixed direction per point, from a hash of its position
    const glm::uvec3 u = glm::floatBitsToUint(p);
    std::mt19937 random(u.x * 73856093u ^ u.y * 19349663u ^ u.z * 83492791u);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    return vec3(normal(random), normal(random), normal(random));
  };
  const ImplicitSurface s = test::analytic([&](vec3 p) { return sphere.distance(p); },
                                           [&](vec3 p) { return glm::normalize(sphere.normal(p) + 0.14f * noise(p)); });
  const vec3 seed[] = {vec3(1, 0, 0)};
  MarchCounts counts;
  const TriangleMesh m = test::march(s, vec3(-1), vec3(1), 0.1f, seed, counts);
  test::expect_one_closed_surface(m, 2);
  EXPECT_LT(counts.crease_vertices, counts.cubes_crossed / 20);
}

class MeshCreasesCli : public test::CliTest {};

// A scanned box's RIMLS surface keeps its edges sharp (Öztireli et al. 2009), and so does
// its mesh: `pss mesh --surface rimls` puts vertices on them unless --crease-angle 180;
// either way the mesh is one closed surface.
TEST_F(MeshCreasesCli, ABoxsSamplesGiveSharpEdges) {
  const TurnedBox box = turned_box();
  const std::string input = write("box.pwn", box_samples(box, 24000));
  const auto mesh = [&](const std::string& name, const std::string& flags) {
    const test::CliResult r = test::run_pss("mesh " + input + " -o " + path(name + ".ply") +
                                            " --surface rimls --progress never --stats " + path(name + ".json") +
                                            " " + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(path(name + ".json"));
    return std::pair{test::read_mesh(path(name + ".ply")), nlohmann::json::parse(in)};
  };
  const auto [creased, kept] = mesh("creased", "");
  const auto [chamfered, cut] = mesh("chamfered", "--crease-angle 180");
  EXPECT_EQ(kept["params"]["crease_angle"], kDefaultCreaseAngle);
  EXPECT_EQ(cut["params"]["crease_angle"], 180);
  EXPECT_GT(kept["band"]["crease_vertices"].get<int>(), 100);
  EXPECT_GT(kept["band"]["crease_flips"].get<int>(), 50);
  EXPECT_EQ(cut["band"]["crease_vertices"], 0);
  const float cell = kept["params"]["cell"];
  const std::vector<float> with = edge_distances(box, creased, cell), without = edge_distances(box, chamfered, cell);
  std::printf("the edges' mean distance to the mesh of the samples: %.4f cubes with its creases, %.4f without\n",
              mean(with), mean(without));
  EXPECT_LT(mean(with), 0.5 * mean(without));
  EXPECT_EQ(test::crossing_triangle_pairs(creased), 0);
  // A closed box, with or without its creases: outside its edges, where a sample across the
  // crease says nothing of the side, no sheet of the wrong sign (7 components and 120
  // boundary edges when it did).
  test::expect_one_closed_surface(creased, 2);
  test::expect_one_closed_surface(chamfered, 2);
}

TEST_F(MeshCreasesCli, ACreaseAngleOutsideItsRangeIsRefused) {
  const std::string input = write("box.pwn", box_samples(turned_box(), 2000));
  for (const char* angle : {"0", "-5", "181", "nan"})
    expect_clean_failure("mesh " + input + " -o " + path("m.ply") + " --crease-angle " + angle, "--crease-angle",
                         path("m.ply"));
  // The library refuses it too.
  test::SampleOptions o;
  o.count = 500;
  MeshParams params;
  params.projection = ProjectionParams::from_h(0.3f);
  for (const float angle : {0.0f, 181.0f, std::nanf("")}) {
    params.crease_angle = angle;
    const std::string error = test::error_of([&] {
      Stats stats;
      mesh_cloud(test::sample(test::Sphere{}, o), params, Backend::cpu, stats);
    });
    EXPECT_NE(error.find("the crease angle must lie in (0, 180]"), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace pss
