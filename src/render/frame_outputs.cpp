#include "pss/render/frame_outputs.hpp"

#include <vector>

#include "pss/io/ply.hpp"
#include "pss/render/camera_file.hpp"

namespace pss {

FrameSummary summarize(const RenderedFrame& frame) {
  FrameSummary s;
  s.rays = std::int64_t(frame.hits.size());
  s.secondary_rays = frame.secondary_rays;
  std::int64_t iterations = 0;
  for (const Hit& h : frame.hits) {
    s.iterations += h.iterations;
    if (!h.found()) continue;
    ++s.hits;
    iterations += h.iterations;
    if (h.flags & kHitConverged) ++s.converged;
    if (h.flags & kHitCapped) ++s.capped;
  }
  s.mean_iterations = s.hits ? double(iterations) / double(s.hits) : 0.0;
  return s;
}

void write_hits_ply(const std::filesystem::path& path, const RenderedFrame& frame) {
  PointCloud cloud;
  std::vector<std::int32_t> px, py;
  const int width = frame.camera.width;
  for (std::size_t i = 0; i < frame.hits.size(); ++i) {
    const Hit& h = frame.hits[i];
    if (!h.found()) continue;
    const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
    cloud.positions.push_back(h.point);
    cloud.normals.push_back(face_viewer(h.normal, frame.camera.primary_ray(x, y).dir));
    px.push_back(x);
    py.push_back(y);
  }
  const PlyIntProperty extra[] = {{"px", px}, {"py", py}};
  write_ply(path, cloud, extra);
}

void record_frame(Stats& stats, const RenderedFrame& frame) {
  const FrameSummary s = summarize(frame);
  const Camera& c = frame.camera;
  auto& v = stats.values();
  v["rays"] = s.rays;
  v["hits"] = s.hits;
  v["secondary_rays"] = s.secondary_rays;
  v["mean_iterations"] = s.mean_iterations;
  v["primary_iterations"] = s.iterations;
  v["hits_converged"] = s.converged;
  v["hits_capped"] = s.capped;
  v["width"] = c.width;
  v["height"] = c.height;
  v["camera"] = camera_to_json(c);
}

}  // namespace pss
