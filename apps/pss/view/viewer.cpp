#include "viewer.hpp"

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/gl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/io/output_file.hpp"
#include "pss/render/camera_file.hpp"
#include "pss/render/frame_outputs.hpp"
#include "pss/io/image_8bit.hpp"
#include "pss/render/image.hpp"
#include "render_thread.hpp"
#include "script.hpp"

namespace pss::app::view {

namespace {

// The six views of the numbered keys and the panel: front, right, back, left, top, bottom.
constexpr float kPresets[6][2] = {{0, 0}, {90, 0}, {180, 0}, {270, 0}, {0, 89.9f}, {0, -89.9f}};
constexpr float kDegreesPerPixel = 0.3f;

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

// The frame as a texture, at whatever level it came.
struct FrameTexture {
  GLuint id = 0;
  int width = 0, height = 0;
  void upload(const Image& image) {
    if (image.width == 0) return;
    if (!id) glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const std::vector<std::uint8_t> rgb = to_srgb8(image);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    width = image.width;
    height = image.height;
  }
};

class Viewer {
 public:
  // The script and the camera file are read first (run_viewer), so that a bad one is refused
  // before any window opens.
  Viewer(const ViewerOptions& o, GLFWwindow* window, std::vector<Step> steps, std::optional<nlohmann::json> camera)
      : o_(o), window_(window), settings_(o.settings), orbit_(o.orbit), fixed_camera_(camera), steps_(std::move(steps)) {
    open(o.file.input);
  }

  int loop() {
    while (!glfwWindowShouldClose(window_)) {
      glfwWaitEventsTimeout(1.0 / 60);
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      handle_input();
      int w = 0, h = 0;
      glfwGetFramebufferSize(window_, &w, &h);
      if (w != framebuffer_.x || h != framebuffer_.y) {  // a resized window: frames of its size
        framebuffer_ = glm::ivec2(w, h);
        dirty_ = true;
      }
      panel();
      if (!run_script()) break;
      if (dirty_ && renderer_) {
        request_ = renderer_->request(camera(), settings_);
        requested_at_ = std::chrono::steady_clock::now();
        first_shown_ = 0;
        dirty_ = false;
      }
      if (renderer_ && renderer_->poll(shown_)) {
        texture_.upload(shown_.frame.image);
        report_timing();
        if (!shown_.error.empty() && shown_.error != last_error_) std::fprintf(stderr, "pss view: %s\n", shown_.error.c_str());
        last_error_ = shown_.error;
      }
      draw();
    }
    return status_;
  }

 private:
  void open(const std::string& path) {
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
    std::snprintf(path_, sizeof path_, "%s", path.c_str());
  }

  // The open scene's (a cloud's, points/cloud.hpp): camera files hold world positions.
  glm::dvec3 origin() const { return renderer_ ? renderer_->info().origin : glm::dvec3(0.0); }

  Camera camera() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    w = std::max(w, 1);
    h = std::max(h, 1);
    // A camera file's eye is a world position, placed about the scene's origin (checked on loading).
    if (fixed_camera_) return camera_from_json(*fixed_camera_, w, h, "camera", origin());
    return orbit_.camera(renderer_ ? renderer_->bounds() : Aabb{}, w, h);
  }

  void moved() {
    fixed_camera_.reset();
    dirty_ = true;
  }

  void handle_input() {
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureMouse) {
      const ImVec2 d = io.MouseDelta;
      if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && (d.x != 0 || d.y != 0)) {
        orbit_.azimuth -= kDegreesPerPixel * d.x;
        orbit_.elevation = std::clamp(orbit_.elevation + kDegreesPerPixel * d.y, -89.9f, 89.9f);
        moved();
      }
      if ((ImGui::IsMouseDown(ImGuiMouseButton_Right) || ImGui::IsMouseDown(ImGuiMouseButton_Middle)) &&
          (d.x != 0 || d.y != 0)) {
        const float scale = 1.0f / (orbit_.zoom * std::max(1.0f, io.DisplaySize.y));
        orbit_.pan += vec2(-d.x, d.y) * scale;
        moved();
      }
      if (io.MouseWheel != 0) {
        orbit_.zoom = std::clamp(orbit_.zoom * std::pow(1.15f, io.MouseWheel), 0.05f, 200.0f);
        moved();
      }
    }
    // R resets the view, 1–6 pick the presets (ImGui 1.86 names no such keys: GLFW's state).
    const int keys[7] = {GLFW_KEY_R, GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5, GLFW_KEY_6};
    for (int k = 0; k < 7; ++k) {
      const bool down = glfwGetKey(window_, keys[k]) == GLFW_PRESS;
      if (down && !key_down_[k] && !io.WantCaptureKeyboard) reset_view(k == 0 ? 0 : k - 1);
      key_down_[k] = down;
    }
  }

  void reset_view(int preset) {
    orbit_ = o_.orbit;
    orbit_.azimuth = kPresets[preset][0];
    orbit_.elevation = kPresets[preset][1];
    moved();
  }

  void panel() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("pss view");
    if (ImGui::InputText("file", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue)) open(path_);
    if (!load_error_.empty()) error_text(load_error_);
    if (!renderer_) {
      ImGui::End();
      return;
    }
    const SceneInfo& info = renderer_->info();
    ImGui::TextUnformatted(info.description.c_str());
    figures();
    ViewSettings s = settings_;
    if (ImGui::CollapsingHeader("Surface", ImGuiTreeNodeFlags_DefaultOpen)) info.is_volume ? volume_panel(s, info) : cloud_panel(s);
    if (ImGui::CollapsingHeader("Rays", ImGuiTreeNodeFlags_DefaultOpen)) {
      ImGui::Checkbox("shadows", &s.shadows);
      ImGui::SameLine();
      ImGui::Checkbox("reflections", &s.reflections);
      int backend = s.backend == Backend::cuda ? 1 : 0;
      const char* backends[] = {"cpu", "cuda"};
      if (ImGui::Combo("backend", &backend, backends, cuda::built() && cuda::device_count() > 0 ? 2 : 1))
        s.backend = backend ? Backend::cuda : Backend::cpu;
    }
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) view_panel();
    if (!shown_.error.empty()) error_text(shown_.error);
    ImGui::End();
    if (!(s == settings_)) {
      settings_ = s;
      dirty_ = true;
    }
  }

  // With --script, how long the current request took to show its first (reduced) frame and
  // its full-size one, on stdout (bench/ reads it).
  void report_timing() {
    if (o_.script.empty() || shown_.request != request_ || !shown_.error.empty()) return;
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

  static void error_text(const std::string& message) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
    ImGui::TextWrapped("%s", message.c_str());
    ImGui::PopStyleColor();
  }

  void figures() {
    if (shown_.frame.image.width == 0) {
      ImGui::TextUnformatted("rendering...");
      return;
    }
    const FrameSummary f = summarize(shown_.frame);
    ImGui::Text("%dx%d (1/%d)  %.1f ms  %.2f Mrays/s", shown_.frame.image.width, shown_.frame.image.height,
                shown_.factor, 1e3 * shown_.seconds, shown_.seconds > 0 ? 1e-6 * double(f.rays) / shown_.seconds : 0.0);
    ImGui::Text("hits %lld  projections/hit %.2f  capped %lld", (long long)f.hits, f.mean_iterations, (long long)f.capped);
  }

  void cloud_panel(ViewSettings& s) {
    ImGui::InputFloat("h", &s.h, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::InputFloat("rho (0: 2h)", &s.rho, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue);
    int support = s.adaptive_support ? 0 : 1;
    const char* supports[] = {"adaptive", "global"};
    if (ImGui::Combo("support", &support, supports, 2)) s.adaptive_support = support == 0;
    int surface = int(s.surface);
    const char* surfaces[] = {"mls", "apss", "rimls"};  // SurfaceOperator's order
    if (ImGui::Combo("surface", &surface, surfaces, 3)) s.surface = SurfaceOperator(surface);
    ImGui::InputFloat("epsilon", &s.epsilon, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SliderInt("iterations", &s.iterations, 1, 8);
    int secondary = s.secondary_full ? 0 : 1;
    const char* modes[] = {"full", "paper"};
    if (ImGui::Combo("secondary", &secondary, modes, 2)) s.secondary_full = secondary == 0;
  }

  void volume_panel(ViewSettings& s, const SceneInfo& info) {
    ImGui::Checkbox("high gradient (theta2)", &s.volume.gradient);
    if (s.volume.gradient) {
      ImGui::SliderFloat("threshold", &s.volume.threshold, 0, 1, "%.3f");
    } else {
      ImGui::PlotHistogram("##values", info.histogram.data(), int(info.histogram.size()), 0, nullptr, 0, FLT_MAX,
                           ImVec2(0, 48));
      ImGui::SliderFloat("iso", &s.volume.iso, info.value_min, info.value_max, "%.4g");
    }
    int method = s.volume.method == VolumeMethod::predictor ? 0 : 1;
    const char* methods[] = {"predictor", "predictor-corrector"};
    if (ImGui::Combo("method", &method, methods, 2))
      s.volume.method = method == 0 ? VolumeMethod::predictor : VolumeMethod::predictor_corrector;
    ImGui::Checkbox("Figure 2: where the projections moved", &s.debug_projection);
    ImGui::InputFloat("h (voxels)", &s.volume.h, 0, 0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue);
  }

  void view_panel() {
    bool changed = ImGui::SliderFloat("azimuth", &orbit_.azimuth, -180, 360, "%.1f");
    changed |= ImGui::SliderFloat("elevation", &orbit_.elevation, -89.9f, 89.9f, "%.1f");
    changed |= ImGui::SliderFloat("fov", &orbit_.fov, 1, 170, "%.1f");
    changed |= ImGui::SliderFloat("zoom", &orbit_.zoom, 0.05f, 200, "%.3g", ImGuiSliderFlags_Logarithmic);
    if (changed) moved();
    for (int k = 0; k < 6; ++k) {
      static const char* names[] = {"front", "right", "back", "left", "top", "bottom"};
      if (k) ImGui::SameLine();
      if (ImGui::SmallButton(names[k])) reset_view(k);
    }
    ImGui::InputText("camera file", camera_path_, sizeof camera_path_);
    if (ImGui::Button("save camera")) save_camera(camera_path_);
    ImGui::SameLine();
    if (ImGui::Button("load camera")) load_camera(camera_path_);
    ImGui::InputText("screenshot", shot_path_, sizeof shot_path_);
    if (ImGui::Button("save screenshot")) pending_shot_ = shot_path_;
    if (!view_message_.empty()) ImGui::TextUnformatted(view_message_.c_str());
  }

  void save_camera(const std::string& path) {
    try {
      OutputSet outputs({}, {path});
      write_text_file(path, nlohmann::json{{"camera", camera_to_json(camera(), origin())}}.dump(2) + "\n");
      outputs.commit();
      view_message_ = "wrote " + path;
    } catch (const Error& e) {
      view_message_ = one_line(e.what());
    }
  }

  void load_camera(const std::string& path) {
    try {
      fixed_camera_ = read_camera_json(path);
      dirty_ = true;
      view_message_ = "loaded " + path;
    } catch (const Error& e) {
      view_message_ = one_line(e.what());
    }
  }

  // The full-size frame of the current view as an image (the format its name says), its
  // camera and counts as JSON (what --stats writes) and its primary hits as PLY (what --hits
  // writes), beside each other.
  void write_screenshot(const std::string& image) {
    const std::filesystem::path json = std::filesystem::path(image).replace_extension(".json");
    const std::filesystem::path hits = std::filesystem::path(image).replace_extension(".ply");
    OutputSet outputs({}, {image, json, hits});
    write_frame_image(image, shown_.frame, false);
    write_hits(hits, shown_.frame);
    Stats stats;
    record_frame(stats, shown_.frame);
    stats.values()["frame_seconds"] = shown_.seconds;
    stats.write(json);
    outputs.commit();
    std::printf("wrote %s\n", image.c_str());
  }

  bool full_frame_shown() const {
    return renderer_ && request_ && renderer_->finished(request_) && shown_.request == request_ &&
           (shown_.factor == 1 || !shown_.error.empty());
  }

  // One step a frame while steps are left; waits hold the script without holding the UI.
  // Returns false to leave the loop.
  bool run_script() {
    if (!pending_shot_.empty() && full_frame_shown()) {
      try {
        write_screenshot(pending_shot_);
        view_message_ = "wrote " + pending_shot_;
      } catch (const Error& e) {
        view_message_ = one_line(e.what());
      }
      pending_shot_.clear();
    }
    if (o_.script.empty()) return true;
    if (dirty_ && renderer_) return true;  // the last step's request goes out first
    if (frames_ < 3) return true;  // ImGui lays a window out over its first frames
    if (next_step_ == steps_.size()) return false;
    const Step& s = steps_[next_step_];
    try {
      if (s.verb == "window" && !renderer_) {
        window_shot_ = (std::filesystem::path(o_.screenshot_dir) / (s.args[0] + ".png")).string();
      } else if (s.verb == "wait" || s.verb == "screenshot" || s.verb == "window") {
        if (!renderer_) throw Error(load_error_);
        if (!full_frame_shown()) return true;
        const std::string png = (std::filesystem::path(o_.screenshot_dir) / (s.args.empty() ? "" : s.args[0] + ".png")).string();
        if (s.verb == "screenshot") write_screenshot(png);
        if (s.verb == "window") window_shot_ = png;  // read back after this frame is drawn
      } else if (s.verb == "view") {
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
      } else if (s.verb == "quit") {
        return false;
      }
    } catch (const Error& e) {
      std::fprintf(stderr, "pss view: error: %s:%d: %s\n", o_.script.c_str(), s.line, one_line(e.what()).c_str());
      status_ = 1;
      return false;
    }
    ++next_step_;
    return true;
  }

  // The drawn window, panel included (rows from the bottom in OpenGL).
  void write_window(int w, int h) {
    std::vector<std::uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3), flipped(rgb.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    const std::size_t row = std::size_t(w) * 3;
    for (int y = 0; y < h; ++y) std::copy_n(&rgb[std::size_t(h - 1 - y) * row], row, &flipped[std::size_t(y) * row]);
    try {
      OutputSet outputs({}, {window_shot_});
      write_png(window_shot_, w, h, flipped);
      outputs.commit();
      std::printf("wrote %s\n", window_shot_.c_str());
    } catch (const Error& e) {
      std::fprintf(stderr, "pss view: %s\n", one_line(e.what()).c_str());
      status_ = 1;
    }
    window_shot_.clear();
  }

  void draw() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (texture_.id)
      ImGui::GetBackgroundDrawList()->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture_.id)),
                                               ImVec2(0, 0), ImGui::GetIO().DisplaySize);
    ImGui::Render();
    glViewport(0, 0, w, h);
    glClearColor(0.1f, 0.1f, 0.12f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!window_shot_.empty()) write_window(w, h);
    glfwSwapBuffers(window_);
    ++frames_;
  }

  const ViewerOptions& o_;
  GLFWwindow* window_;
  ViewSettings settings_;
  Orbit orbit_;
  std::optional<nlohmann::json> fixed_camera_;  // a camera file's (render/camera_file.hpp)
  std::unique_ptr<RenderThread> renderer_;
  std::uint64_t request_ = 0;
  bool dirty_ = false;
  Published shown_;
  FrameTexture texture_;
  std::string load_error_, last_error_, view_message_, pending_shot_, window_shot_;
  std::vector<Step> steps_;
  std::size_t next_step_ = 0;
  int status_ = 0;
  glm::ivec2 framebuffer_{0};
  std::chrono::steady_clock::time_point requested_at_;
  int first_shown_ = 0;
  double first_seconds_ = 0, first_frame_seconds_ = 0;
  int frames_ = 0;
  bool key_down_[7] = {};
  char path_[1024] = {};
  char camera_path_[1024] = "camera.json";
  char shot_path_[1024] = "screenshot.png";
};

}  // namespace

int run_viewer(const ViewerOptions& options) {
  std::vector<Step> steps;
  std::optional<nlohmann::json> camera;
  try {
    if (!options.script.empty()) steps = read_script(options.script);
    if (!options.camera_file.empty()) camera = read_camera_json(options.camera_file);
  } catch (const Error& e) {
    std::fprintf(stderr, "pss view: error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
  glfwSetErrorCallback([](int, const char* message) { std::fprintf(stderr, "pss view: GLFW: %s\n", message); });
  if (!glfwInit()) {
    std::fprintf(stderr, "pss view: error: cannot open a window (no display? set DISPLAY, or run under xvfb-run)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "pss view", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "pss view: error: cannot create an OpenGL 3.3 window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");
  int status = 1;
  try {
    Viewer viewer(options, window, std::move(steps), camera);
    status = viewer.loop();
  } catch (const Error& e) {
    std::fprintf(stderr, "pss view: error: %s\n", one_line(e.what()).c_str());
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace pss::app::view
