#include "session.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/io/output_file.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/render/camera_file.hpp"
#include "pss/render/frame_outputs.hpp"

namespace pss::app::view {

namespace {

float number_of(const Step& s, std::size_t i, const std::string& script) {
  const std::string& t = s.args[i];
  float v = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size())
    throw file_error(script + ":" + std::to_string(s.line), "expected a number (got " + quote(t) + ")");
  return v;
}

// The step's value, one of `choices`.
std::string choice_of(const Step& s, std::initializer_list<const char*> choices, const std::string& script) {
  std::string listed;
  for (const char* c : choices) {
    if (s.args[1] == c) return c;
    listed += (listed.empty() ? "" : " or ") + std::string(c);
  }
  throw file_error(script + ":" + std::to_string(s.line), "expected " + listed + " (got " + quote(s.args[1]) + ")");
}

bool switch_of(const Step& s, const std::string& script) { return choice_of(s, {"on", "off"}, script) == "on"; }

// A panel value by name, as the script sets it; the render thread checks its range.
void set_value(ViewSettings& v, const Step& s, const std::string& script) {
  const std::string& name = s.args[0];
  const std::string& value = s.args[1];
  if (name == "h") v.h = number_of(s, 1, script);
  else if (name == "rho") v.rho = number_of(s, 1, script);
  else if (name == "support") v.adaptive_support = choice_of(s, {"adaptive", "global"}, script) == "adaptive";
  else if (name == "surface") v.surface = surface_operator_of(choice_of(s, {"mls", "apss", "rimls"}, script));
  else if (name == "epsilon") v.epsilon = number_of(s, 1, script);
  else if (name == "iterations") v.iterations = int(number_of(s, 1, script));
  else if (name == "secondary") v.secondary_full = value != "paper";
  else if (name == "borders") v.borders = border_choice_of(choice_of(s, {"auto", "clip", "extend"}, script));
  else if (name == "shadows") v.shadows = switch_of(s, script);
  else if (name == "reflections") v.reflections = switch_of(s, script);
  else if (name == "debug") v.debug_projection = switch_of(s, script);
  else if (name == "iso") v.volume.iso = number_of(s, 1, script);
  else if (name == "threshold") v.volume.threshold = number_of(s, 1, script);
  else if (name == "gradient") v.volume.gradient = switch_of(s, script);
  else if (name == "method")
    v.volume.method = value == "predictor" ? VolumeMethod::predictor : VolumeMethod::predictor_corrector;
  else throw file_error(script + ":" + std::to_string(s.line), "no panel value " + quote(name));
}

}  // namespace

Session::Session(const ViewerOptions& options, std::vector<Step> steps, std::optional<nlohmann::json> camera,
                 std::function<void(const std::string&)> write_window)
    : o_(options),
      write_window_(std::move(write_window)),
      settings_(options.settings),
      orbit_(options.orbit),
      fixed_camera_(std::move(camera)),
      steps_(std::move(steps)) {
  open(options.file.input);
}

void Session::open(const std::string& path) {
  renderer_.reset();
  load_error_.clear();
  try {
    VolumeOptions file = o_.file;
    file.input = path;
    ViewSettings settings = o_.settings;
    std::unique_ptr<Scene> scene = open_scene(file, settings);
    settings_ = settings;
    renderer_ = std::make_unique<RenderThread>(std::move(scene));
    dirty_ = true;
  } catch (const Error& e) {
    load_error_ = one_line(e.what());
    std::fprintf(stderr, "pss view: %s\n", load_error_.c_str());
  } catch (const std::bad_alloc&) {
    load_error_ = "out of memory reading " + path;
  }
}

bool Session::update(glm::ivec2 size) {
  if (size != size_) {  // a resized window: frames of its size
    size_ = size;
    dirty_ = true;
  }
  if (!renderer_) return false;
  if (dirty_) {
    request_ = renderer_->request(camera(), settings_, with_hits_);
    timed_ = !with_hits_;  // a screenshot's second render of a view is not the view's timing
    requested_at_ = std::chrono::steady_clock::now();
    first_shown_ = 0;
    dirty_ = false;
  }
  if (!renderer_->poll(shown_)) return false;
  shown_summary_ = summarize(*shown_.frame);
  report_timing();
  if (!shown_.error.empty() && shown_.error != last_error_) std::fprintf(stderr, "pss view: %s\n", shown_.error.c_str());
  last_error_ = shown_.error;
  return true;
}

void Session::moved() {
  fixed_camera_.reset();
  dirty_ = true;
}

// The open scene's (a cloud's, points/cloud.hpp): camera files hold world positions.
glm::dvec3 Session::origin() const { return renderer_ ? renderer_->info().origin : glm::dvec3(0.0); }

Camera Session::camera() const {
  const int w = std::max(size_.x, 1), h = std::max(size_.y, 1);
  // A camera file's eye is a world position, placed about the scene's origin (checked on loading).
  if (fixed_camera_) return camera_from_json(*fixed_camera_, w, h, "camera", origin());
  return orbit_.camera(renderer_ ? renderer_->bounds() : Aabb{}, w, h);
}

void Session::save_camera(const std::string& path) {
  try {
    OutputSet outputs({}, {path});
    write_text_file(path, nlohmann::json{{"camera", camera_to_json(camera(), origin())}}.dump(2) + "\n");
    outputs.commit();
    message_ = "wrote " + path;
  } catch (const Error& e) {
    message_ = one_line(e.what());
  }
}

void Session::load_camera(const std::string& path) {
  try {
    fixed_camera_ = read_camera_json(path);
    dirty_ = true;
    message_ = "loaded " + path;
  } catch (const Error& e) {
    message_ = one_line(e.what());
  }
}

// The full-size frame of the current view as an image (the format its name says), its camera
// and counts as JSON (what --stats writes) and its primary hits as PLY (what --hits writes),
// beside each other.
void Session::write_screenshot(const std::string& image) {
  // Only the frame a refused request left on screen can lack them (shot_ready asks for them).
  if (shown_.frame->hits.empty())
    throw file_error(image, "cannot write: the last request was refused (" + shown_.error +
                                ") and the frame on screen kept no hits; set an accepted value first");
  const std::filesystem::path json = std::filesystem::path(image).replace_extension(".json");
  const std::filesystem::path hits = std::filesystem::path(image).replace_extension(".ply");
  OutputSet outputs({}, {image, json, hits});
  write_frame_image(image, *shown_.frame, false);
  write_hits(hits, *shown_.frame);
  Stats stats;
  record_frame(stats, *shown_.frame);
  stats.values()["frame_seconds"] = shown_.seconds;
  stats.write(json);
  outputs.commit();
  std::printf("wrote %s\n", image.c_str());
}

bool Session::full_frame_shown() const {
  return renderer_ && request_ && renderer_->finished(request_) && shown_.request == request_ &&
         (shown_.factor == 1 || !shown_.error.empty());
}

// Whether the full frame shown can be written as a screenshot; if it came without its hits,
// asks for it again with them (the same view: the same image) and says no until it is there.
bool Session::shot_ready() {
  if (!full_frame_shown()) return false;
  if (!shown_.error.empty() || !shown_.frame->hits.empty()) return true;
  if (!with_hits_) {
    with_hits_ = true;
    dirty_ = true;
  }
  return false;
}

// With --script, how long the current request took to show its first (reduced) frame and its
// full-size one, on stdout (bench/ reads it).
void Session::report_timing() {
  if (o_.script.empty() || !timed_ || shown_.request != request_ || !shown_.error.empty()) return;
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - requested_at_).count();
  if (first_shown_ == 0) {
    first_shown_ = shown_.factor;
    first_seconds_ = since;
    first_frame_seconds_ = shown_.seconds;
  }
  if (shown_.factor == 1)
    std::printf("view timing: first frame at 1/%d in %.4f s (its render %.4f s), full size in %.4f s (its render %.4f s)\n",
                first_shown_, first_seconds_, first_frame_seconds_, since, shown_.seconds);
}

// One step a call while steps are left; waits hold the script without holding the caller.
bool Session::run_script(bool ready) {
  if (!pending_shot_.empty() && shot_ready()) {
    try {
      write_screenshot(pending_shot_);
      message_ = "wrote " + pending_shot_;
    } catch (const Error& e) {
      message_ = one_line(e.what());
    }
    pending_shot_.clear();
    with_hits_ = false;
  }
  if (o_.script.empty()) return true;
  if (dirty_ && renderer_) return true;  // the last step's request goes out first
  if (!ready) return true;
  if (next_step_ == steps_.size()) return false;
  const Step& s = steps_[next_step_];
  try {
    if (s.verb == "window" && !write_window_)
      throw Error("no window to write: pss view --headless has none (use screenshot)");
    if (s.verb == "window" && !renderer_) {
      write_window_((std::filesystem::path(o_.screenshot_dir) / (s.args[0] + ".png")).string());
    } else if (s.verb == "wait" || s.verb == "screenshot" || s.verb == "window") {
      if (!renderer_) throw Error(load_error_);
      if (!(s.verb == "screenshot" ? shot_ready() : full_frame_shown())) return true;
      const std::string png = (std::filesystem::path(o_.screenshot_dir) / (s.args.empty() ? "" : s.args[0] + ".png")).string();
      if (s.verb == "screenshot") write_screenshot(png);
      if (s.verb == "window") write_window_(png);
    } else if (s.verb == "quit") {
      return false;
    } else {
      step(s);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "pss view: error: %s:%d: %s\n", o_.script.c_str(), s.line, one_line(e.what()).c_str());
    status_ = 1;
    return false;
  }
  ++next_step_;
  with_hits_ = false;  // until the next screenshot
  return true;
}

// A step that changes the view or the settings.
void Session::step(const Step& s) {
  if (s.verb == "view") {
    orbit_.azimuth = number_of(s, 0, o_.script);
    orbit_.elevation = number_of(s, 1, o_.script);
    moved();
  } else if (s.verb == "zoom") {
    orbit_.zoom = number_of(s, 0, o_.script);
    moved();
  } else if (s.verb == "pan") {
    orbit_.pan = vec2(number_of(s, 0, o_.script), number_of(s, 1, o_.script));
    moved();
  } else if (s.verb == "fov") {
    orbit_.fov = number_of(s, 0, o_.script);
    moved();
  } else if (s.verb == "camera") {
    fixed_camera_ = read_camera_json(s.args[0]);
    dirty_ = true;
  } else if (s.verb == "set") {
    set_value(settings_, s, o_.script);
    dirty_ = true;
  }
}

}  // namespace pss::app::view
