#include "render_options.hpp"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <optional>

#include "numbers.hpp"
#include "output_options.hpp"
#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/io/output_format.hpp"
#include "pss/render/camera_file.hpp"
#include "pss/render/frame_outputs.hpp"

namespace pss::app {

namespace {

// "A<sep>B" as two numbers, the whole text consumed.
template <class T>
std::optional<std::pair<T, T>> parse_pair(const std::string& text, char separator) {
  const auto at = text.find(separator);
  if (at == std::string::npos) return std::nullopt;
  T a{}, b{};
  const char* end = text.data() + text.size();
  const auto ra = std::from_chars(text.data(), text.data() + at, a);
  const auto rb = std::from_chars(text.data() + at + 1, end, b);
  if (ra.ec != std::errc() || ra.ptr != text.data() + at || rb.ec != std::errc() || rb.ptr != end) return std::nullopt;
  return std::make_pair(a, b);
}

std::string check_size(const std::string& text) {
  const auto wh = parse_pair<int>(text, 'x');
  if (!wh) return "expected WIDTHxHEIGHT, e.g. 512x512 (got " + quote(text) + ")";
  if (wh->first < 1 || wh->second < 1 || wh->first > kMaxImageSide || wh->second > kMaxImageSide)
    return "width and height must be between 1 and " + std::to_string(kMaxImageSide) + " (got " + quote(text) + ")";
  if (static_cast<long long>(wh->first) * wh->second > kMaxImagePixels)
    return "at most " + std::to_string(kMaxImagePixels) + " pixels in all, e.g. 8192x8192 (got " + quote(text) + ")";
  return {};
}

// "X,Y,Z" as three finite numbers, the whole text consumed; in double, so that a world
// point far from zero keeps its digits (--look-at on a georeferenced cloud).
std::optional<glm::dvec3> parse_triple(const std::string& text) {
  const auto first = text.find(',');
  if (first == std::string::npos) return std::nullopt;
  const auto yz = parse_pair<double>(text.substr(first + 1), ',');
  const auto x = parse_pair<double>(text.substr(0, first) + ",0", ',');
  if (!x || !yz) return std::nullopt;
  const glm::dvec3 v(x->first, yz->first, yz->second);
  if (!(glm::length(v) < 1e30)) return std::nullopt;  // false for NaN and infinity too
  return v;
}

CLI::Validator triple(bool nonzero) {
  return CLI::Validator(
      [nonzero](std::string& text) -> std::string {
        const auto v = parse_triple(text);
        if (!v) return "expected X,Y,Z, three finite numbers less than 1e30 from zero (got " + quote(text) + ")";
        if (nonzero && !(glm::length(*v) > 0)) return "expected a non-zero direction X,Y,Z (got " + quote(text) + ")";
        return {};
      },
      "X,Y,Z", "triple");
}

std::string check_view(const std::string& text) {
  const auto ae = parse_pair<float>(text, ',');
  if (!ae) return "expected AZIMUTH,ELEVATION in degrees, e.g. 30,20 (got " + quote(text) + ")";
  // from_chars reads "nan" and "inf"; the azimuth may be any finite angle.
  if (!std::isfinite(ae->first)) return "the azimuth must be a finite number of degrees (got " + quote(text) + ")";
  if (!(ae->second >= -90 && ae->second <= 90))
    return "the elevation must be between -90 and 90 degrees (got " + quote(text) + ")";
  return {};
}

}  // namespace

void add_render_options(CLI::App& command, RenderOptions& o) {
  command
      .add_option("-o,--output", o.output,
                  "output image, its format by extension: .png, .jpg/.jpeg (quality " + std::to_string(kJpegQuality) +
                      ") or .exr (linear RGBA half; Z: the primary ray's distance, inf where it missed; N.X N.Y N.Z: "
                      "the normal facing the camera)")
      ->required()
      ->check(image_output());
  command.add_flag("--transparent", o.transparent,
                   "alpha 0 where the primary ray missed the surface, opaque where it hit (.png, .exr)");
  command
      .add_option_function<std::string>(
          "--size",
          [&o](const std::string& text) {
            const auto wh = *parse_pair<int>(text, 'x');
            o.camera.width = wh.first;
            o.camera.height = wh.second;
          },
          "image size WIDTHxHEIGHT, each side from 1 to " + std::to_string(kMaxImageSide) + " (default 512x512)")
      ->check(CLI::Validator(check_size, "WxH", "size"));
  command
      .add_option_function<std::string>(
          "--view",
          [&o](const std::string& text) {
            const auto ae = *parse_pair<float>(text, ',');
            o.camera.azimuth_deg = ae.first;
            o.camera.elevation_deg = ae.second;
          },
          "orbit the default camera: AZIMUTH,ELEVATION in degrees (default 0,0: from +z, looking along -z, y up)")
      ->check(CLI::Validator(check_view, "AZ,EL", "view"));
  auto* view = command.get_option("--view");
  auto* fov = command.add_option("--fov", o.camera.fov_deg, "vertical field of view in degrees")
                  ->check(finite_range(kMinFovDeg, kMaxFovDeg))
                  ->capture_default_str();
  auto* look_at = command
                      .add_option_function<std::string>(
                          "--look-at",
                          [&o](const std::string& text) {
                            o.camera.has_look_at = true;
                            o.camera.look_at = *parse_triple(text);
                          },
                          "the point the camera orbits and looks at (default: the centre of the object's box)")
                      ->check(triple(false));
  auto* up = command
                 .add_option_function<std::string>(
                     "--up", [&o](const std::string& text) { o.camera.up = vec3(*parse_triple(text)); },
                     "the world's up direction, which --view's elevation is measured from (default 0,1,0)")
                 ->check(triple(true));
  auto* distance = command.add_option("--distance", o.camera.distance,
                                      "the eye's distance from the look-at point (default: the object fills the view; "
                                      "given, --fov zooms)")
                       ->check(finite_positive());
  auto* zoom = command.add_option("--zoom", o.camera.zoom, "divides the eye's distance: 2 comes twice as close")
                   ->check(finite_range(kMinZoom, kMaxZoom))
                   ->capture_default_str();
  auto* roll = command.add_option("--roll", o.camera.roll_deg, "turns the camera about the view direction, degrees counter-clockwise (the picture turns clockwise)")
                   ->check(finite_range(-kMaxRollDeg, kMaxRollDeg))
                   ->capture_default_str();
  auto* camera = command.add_option("--camera", o.camera_file,
                                    "the camera of a JSON file: the \"camera\" that --stats writes (a --stats file "
                                    "loads as it is), instead of the flags that place the camera");
  for (CLI::Option* placing : {view, fov, look_at, up, distance, zoom, roll}) camera->excludes(placing);
  command
      .add_option("--hits", o.hits_path,
                  "write the primary hits as .ply (binary: x y z nx ny nz and the pixel's px py) or .xyz (text: "
                  "x y z nx ny nz)")
      ->check(points_output());
  command.add_option("--frames", o.frames,
                     "render the frame N times and report the median frame's time (as a viewer sees it)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command.add_flag("--shadows", o.shadows, "shadow rays toward the key light");
  command.add_flag("--reflections", o.reflections, "one mirror reflection per primary hit (ray depth 2)");
  command.add_option("--reflectivity", o.reflectivity, "Fresnel reflectance at normal incidence, with --reflections")
      ->check(finite_range(0, 1))
      ->capture_default_str();
  add_compute_options(command, o.compute);
}

void check_render_options(const RenderOptions& o) {
  if (o.transparent && image_format_of(o.output) == ImageFormat::jpeg)
    throw CLI::ValidationError("--transparent", printable(o.output, kPathBytes) +
                                                    " is a JPEG, which has no alpha; name it .png or .exr");
}

Camera make_camera(const RenderOptions& o, const Aabb& bounds, const glm::dvec3& origin) {
  if (!o.camera_file.empty()) return read_camera_file(o.camera_file, o.camera.width, o.camera.height, origin);
  try {
    validate(o.camera);  // each flag is checked; together the view must not look along --up
  } catch (const Error& e) {
    throw Error(std::string("--view, --up: ") + e.what());
  }
  CameraSettings settings = o.camera;
  if (settings.has_look_at) settings.look_at -= origin;
  return Camera::framing(bounds, settings);
}

TraceSettings trace_settings(const RenderOptions& o, const Camera& camera) {
  return TraceSettings::for_camera(camera, o.shadows, o.reflections, o.reflectivity);
}

double frame_seconds(const Stats& stats) {
  return stats.time("primary") + stats.time("secondary") + stats.time("shading");
}

void write_frame_outputs(const RenderOptions& options, const RenderedFrame& frame) {
  write_frame_image(options.output, frame, options.transparent);
  if (!options.hits_path.empty()) write_hits(options.hits_path, frame);
}

void print_written(const RenderOptions& options) {
  for (const std::string* path : {&options.output, &options.hits_path, &options.compute.stats_path})
    if (!path->empty()) std::printf("wrote %s\n", path->c_str());
}

void record_render_stats(Stats& stats, const RenderOptions& options, const RenderedFrame& frame,
                         const TraceSettings& settings, Backend backend, const char* command,
                         const std::string& input) {
  record_frame(stats, frame);
  const double frame_s = frame_seconds(stats);
  record_run(stats, command, input, options.output, backend);
  auto& v = stats.values();
  v["frame_seconds"] = frame_s;
  v["fps"] = 1.0 / frame_s;
  // record_frame wrote the camera itself and the image size; these are the flags behind it.
  const CameraSettings& c = options.camera;
  if (options.camera_file.empty())
    v["view"] = {{"fov_deg", c.fov_deg}, {"azimuth_deg", c.azimuth_deg}, {"elevation_deg", c.elevation_deg},
                 {"up", {c.up.x, c.up.y, c.up.z}}, {"distance", c.distance}, {"zoom", c.zoom}, {"roll_deg", c.roll_deg}};
  if (options.camera_file.empty() && c.has_look_at) v["view"]["look_at"] = {c.look_at.x, c.look_at.y, c.look_at.z};
  else
    v["camera_file"] = options.camera_file;
  v["shading"] = {{"shadows", settings.shadows}, {"reflections", settings.reflections},
                  {"reflectivity", settings.shading.reflectivity}};
}

}  // namespace pss::app
