// pss info FILE: what a cloud is, and the h that pss would use for it.
#include <cstdio>

#include "commands.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/points/spacing.hpp"

namespace pss::app {

void add_info_command(CLI::App& app) {
  auto* command = app.add_subcommand("info", "Print a point cloud's size, bounds, sample spacing and suggested h");
  auto path = std::make_shared<std::string>();
  command->add_option("file", *path, "point cloud (.ply, .xyz, .txt, .pts)")->required();
  command->callback([path] {
    const PointCloud cloud = read_point_cloud(*path);
    const Aabb box = cloud.bounds();
    const vec3 size = box.extent();
    std::printf("file            %s\n", path->c_str());
    std::printf("points          %zu%s\n", cloud.size(), cloud.has_normals() ? " (with normals)" : "");
    std::printf("bounds          [%g, %g] x [%g, %g] x [%g, %g]\n", box.lo.x, box.hi.x, box.lo.y, box.hi.y,
                box.lo.z, box.hi.z);
    std::printf("size            %g x %g x %g (diagonal %g)\n", size.x, size.y, size.z, glm::length(size));
    if (cloud.size() >= 2) {
      const SpacingEstimate s = estimate_spacing(cloud.positions);
      std::printf("spacing         %g mean nearest-neighbour distance\n", s.mean_nearest);
      std::printf("suggested h     %g (median distance to the %dth nearest neighbour; rho = 2h = %g)\n", s.suggested_h,
                  s.k, 2 * s.suggested_h);
    }
  });
}

}  // namespace pss::app
