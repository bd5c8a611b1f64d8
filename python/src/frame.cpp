#include "frame.hpp"

#include <cmath>
#include <string>
#include <tuple>
#include <limits>

#include "arrays.hpp"
#include "options.hpp"
#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/render/camera_file.hpp"
#include "pss/render/frame_outputs.hpp"

namespace pss::python {

namespace {

// (azimuth, elevation): two finite numbers of degrees.
std::pair<float, float> view_of(const py::object& value) {
  const Error bad("view: expected (azimuth, elevation), two finite numbers of degrees (got " +
                  shown(value) + ")");
  const py::array_t<double, py::array::forcecast> a = py::array_t<double, py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 1 || a.shape(0) != 2 || !std::isfinite(a.at(0)) || !std::isfinite(a.at(1))) throw bad;
  return {float(a.at(0)), float(a.at(1))};
}

// (width, height): two integers from 1 to kMaxImageSide.
std::pair<int, int> size_of(const py::object& value) {
  const Error bad("size: expected (width, height), two integers from 1 to " + std::to_string(kMaxImageSide) +
                  " (got " + shown(value) + ")");
  const py::array a = py::array::ensure(value);
  if (!a || a.ndim() != 1 || a.shape(0) != 2 || (a.dtype().kind() != 'i' && a.dtype().kind() != 'u')) throw bad;
  const auto wh = py::array_t<std::int64_t, py::array::forcecast>::ensure(a);
  if (wh.at(0) < 1 || wh.at(1) < 1 || wh.at(0) > kMaxImageSide || wh.at(1) > kMaxImageSide) throw bad;
  return {int(wh.at(0)), int(wh.at(1))};
}

}  // namespace

FrameRequest frame_request(const py::dict& o) {
  FrameRequest r;
  CameraSettings& c = r.camera;
  if (is_given(o, "size")) std::tie(c.width, c.height) = size_of(option(o, "size"));
  if (is_given(o, "camera_json")) r.camera_json = nlohmann::json::parse(text(o, "camera_json"), nullptr, false);
  if (is_given(o, "camera_file")) r.camera_file = text(o, "camera_file");
  if (!r.camera_json && r.camera_file.empty()) {
    if (is_given(o, "view")) std::tie(c.azimuth_deg, c.elevation_deg) = view_of(option(o, "view"));
    c.fov_deg = float(number_or(o, "fov", c.fov_deg, kMinFovDeg, kMaxFovDeg));
    if (is_given(o, "look_at")) {
      c.has_look_at = true;
      c.look_at = dvec3_of(option(o, "look_at"), "look_at");
    }
    if (is_given(o, "up")) c.up = vec3_of(option(o, "up"), "up");
    c.distance = positive_or_none(o, "distance").value_or(0.0f);
    c.zoom = float(number_or(o, "zoom", c.zoom, kMinZoom, kMaxZoom));
    c.roll_deg = float(number_or(o, "roll", c.roll_deg, -kMaxRollDeg, kMaxRollDeg));
  }
  validate(c);
  r.shadows = flag(o, "shadows");
  r.reflections = flag(o, "reflections");
  r.reflectivity = float(number_or(o, "reflectivity", ShadingParams{}.reflectivity, 0, 1));
  r.transparent = flag(o, "transparent");
  r.full_output = flag(o, "full_output");
  return r;
}

Camera make_camera(const FrameRequest& r, const Aabb& bounds, const glm::dvec3& origin) {
  const int w = r.camera.width, h = r.camera.height;
  if (!r.camera_file.empty()) return read_camera_file(r.camera_file, w, h, origin);
  if (r.camera_json) return camera_from_json(*r.camera_json, w, h, "camera", origin);
  CameraSettings settings = r.camera;
  settings.look_at -= origin;
  return Camera::framing(bounds, settings);
}

TraceSettings trace_settings(const FrameRequest& r, const Camera& camera) {
  return TraceSettings::for_camera(camera, r.shadows, r.reflections, r.reflectivity);
}

py::dict stats_dict(const Stats& stats) {
  return py::module_::import("json").attr("loads")(stats.to_json().dump());
}

py::object frame_result(RenderedFrame&& frame, Stats& stats, const FrameRequest& r) {
  // An image of background alone looks like a result; the CLI prints its count of hits.
  if (summarize(frame).hits == 0 &&
      PyErr_WarnEx(PyExc_RuntimeWarning,
                   "no ray hit the surface: the image is background alone (h too small for the samples' spacing, "
                   "an iso-value the data barely reach, or a camera turned away?)", 1) != 0)
    throw py::error_already_set();
  const py::ssize_t w = frame.camera.width, h = frame.camera.height;
  const py::ssize_t channels = r.transparent ? 4 : 3;
  py::array image = to_numpy<std::uint8_t>(frame_srgb8(frame, r.transparent), {h, w, channels});
  if (!r.full_output) return image;

  const std::size_t n = frame.hits.size();
  std::vector<std::uint8_t> mask(n);
  std::vector<float> depth(n, std::numeric_limits<float>::infinity());
  std::vector<std::int32_t> iterations(n);
  std::vector<vec3> points(n, vec3(std::numeric_limits<float>::quiet_NaN())), normals(n, vec3(0.0f));
  for (std::size_t i = 0; i < n; ++i) {
    const Hit& hit = frame.hits[i];
    iterations[i] = hit.iterations;
    if (!hit.found()) continue;
    mask[i] = 1;
    depth[i] = hit.t;
    points[i] = hit.point;
    normals[i] = normal_facing_camera(frame, i);
  }
  py::dict hits;
  hits["mask"] = to_numpy<std::uint8_t>(std::move(mask), {h, w}).attr("astype")("bool");
  hits["depth"] = to_numpy<float>(std::move(depth), {h, w});
  hits["iterations"] = to_numpy<std::int32_t>(std::move(iterations), {h, w});
  hits["points"] = world_numpy(std::move(points), frame.origin, {h, w, 3});
  hits["normals"] = to_numpy<float>(std::move(normals), {h, w, 3});
  record_frame(stats, frame);
  return py::make_tuple(image, hits, stats_dict(stats));
}

}  // namespace pss::python
