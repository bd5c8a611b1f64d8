#include "pss/render/frame_outputs.hpp"

#include <limits>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/exr.hpp"
#include "pss/io/image_8bit.hpp"
#include "pss/io/output_format.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/render/camera_file.hpp"

namespace pss {

FrameSummary summarize(const RenderedFrame& frame) {
  FrameSummary s;
  if (frame.hits.empty()) {
    s = frame.summary;  // the hits stayed where they were made (FrameHits::summary)
  } else {
    for (const Hit& h : frame.hits) s.add(h.found(), h.flags & kHitConverged, h.flags & kHitCapped, h.iterations);
    s.finish();
  }
  s.secondary_rays = frame.secondary_rays;
  return s;
}

vec3 normal_facing_camera(const RenderedFrame& frame, std::size_t pixel) {
  const std::size_t width = std::size_t(frame.camera.width);
  const Ray ray = frame.camera.primary_ray(int(pixel % width), int(pixel / width));
  return face_viewer(frame.hits[pixel].normal, ray.dir);
}

std::vector<std::uint8_t> frame_srgb8(const RenderedFrame& frame, bool transparent) {
  const Image& image = frame.image;
  if (!transparent) return to_srgb8(image);
  std::vector<std::uint8_t> rgba(image.pixels.size() * 4);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = linear_to_srgb8(image.pixels[i][c]);
    rgba[4 * i + 3] = frame.hits[i].found() ? 255 : 0;
  }
  return rgba;
}

namespace {

void write_8bit(const std::filesystem::path& path, const RenderedFrame& frame, ImageFormat format, bool transparent) {
  const Image& image = frame.image;
  if (format == ImageFormat::jpeg) {
    if (transparent) throw file_error(path, "cannot write: a JPEG has no alpha for --transparent; name it .png or .exr");
    return write_jpeg(path, image.width, image.height, to_srgb8(image), kJpegQuality);
  }
  write_png(path, image.width, image.height, frame_srgb8(frame, transparent), transparent ? 4 : 3);
}

void write_linear(const std::filesystem::path& path, const RenderedFrame& frame, bool transparent) {
  const std::size_t n = frame.hits.size();
  std::vector<vec4> rgba(n);
  std::vector<float> depth(n, std::numeric_limits<float>::infinity());
  std::vector<vec3> normal(n, vec3(0.0f));
  for (std::size_t i = 0; i < n; ++i) {
    const Hit& h = frame.hits[i];
    // Premultiplied: a transparent pixel has no colour, so compositing over it adds none.
    rgba[i] = transparent && !h.found() ? vec4(0.0f) : vec4(frame.image.pixels[i], 1.0f);
    if (!h.found()) continue;
    depth[i] = h.t;
    normal[i] = normal_facing_camera(frame, i);
  }
  write_exr(path, {frame.image.width, frame.image.height, rgba, depth, normal});
}

}  // namespace

void write_frame_image(const std::filesystem::path& path, const RenderedFrame& frame, bool transparent) {
  const ImageFormat format = image_format_of(path);
  if (format == ImageFormat::exr) write_linear(path, frame, transparent);
  else write_8bit(path, frame, format, transparent);
}

void write_hits(const std::filesystem::path& path, const RenderedFrame& frame) {
  PointCloud cloud;
  cloud.origin = frame.origin;
  std::vector<std::int32_t> px, py;
  const int width = frame.camera.width;
  for (std::size_t i = 0; i < frame.hits.size(); ++i) {
    const Hit& h = frame.hits[i];
    if (!h.found()) continue;
    const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
    cloud.positions.push_back(h.point);
    cloud.normals.push_back(normal_facing_camera(frame, i));
    px.push_back(x);
    py.push_back(y);
  }
  const PlyIntProperty extra[] = {{"px", px}, {"py", py}};
  write_point_cloud(path, cloud, extra);
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
  v["camera"] = camera_to_json(c, frame.origin);
  v["origin"] = {frame.origin.x, frame.origin.y, frame.origin.z};  // the cloud's (cloud.hpp)
}

}  // namespace pss
