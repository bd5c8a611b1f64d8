#include "viewer.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <optional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/gl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/io/image_8bit.hpp"
#include "pss/io/output_file.hpp"
#include "pss/render/camera_file.hpp"
#include "pss/render/image.hpp"
#include "session.hpp"

namespace pss::app::view {

namespace {

// The six views of the numbered keys and the panel: front, right, back, left, top, bottom.
constexpr float kPresets[6][2] = {{0, 0}, {90, 0}, {180, 0}, {270, 0}, {0, 89.9f}, {0, -89.9f}};
constexpr float kDegreesPerPixel = 0.3f;

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
      : o_(o),
        window_(window),
        session_(o, std::move(steps), std::move(camera), [this](const std::string& png) { window_shot_ = png; }) {
    std::snprintf(path_, sizeof path_, "%s", o.file.input.c_str());
  }

  int loop() {
    while (!glfwWindowShouldClose(window_)) {
      glfwWaitEventsTimeout(1.0 / 60);
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      handle_input();
      panel();
      if (!session_.run_script(frames_ >= 3)) break;  // ImGui lays a window out over its first frames
      int w = 0, h = 0;
      glfwGetFramebufferSize(window_, &w, &h);
      if (session_.update(glm::ivec2(w, h))) texture_.upload(session_.shown().frame->image);
      draw();
    }
    return failed_ ? 1 : session_.status();
  }

 private:
  void handle_input() {
    const ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureMouse) {
      Orbit& orbit = session_.orbit();
      const ImVec2 d = io.MouseDelta;
      if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && (d.x != 0 || d.y != 0)) {
        orbit.azimuth -= kDegreesPerPixel * d.x;
        orbit.elevation = std::clamp(orbit.elevation + kDegreesPerPixel * d.y, -89.9f, 89.9f);
        session_.moved();
      }
      if ((ImGui::IsMouseDown(ImGuiMouseButton_Right) || ImGui::IsMouseDown(ImGuiMouseButton_Middle)) &&
          (d.x != 0 || d.y != 0)) {
        const float scale = 1.0f / (orbit.zoom * std::max(1.0f, io.DisplaySize.y));
        orbit.pan += vec2(-d.x, d.y) * scale;
        session_.moved();
      }
      if (io.MouseWheel != 0) {
        orbit.zoom = std::clamp(orbit.zoom * std::pow(1.15f, io.MouseWheel), 0.05f, 200.0f);
        session_.moved();
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
    Orbit& orbit = session_.orbit();
    orbit = o_.orbit;
    orbit.azimuth = kPresets[preset][0];
    orbit.elevation = kPresets[preset][1];
    session_.moved();
  }

  void panel() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("pss view");
    if (ImGui::InputText("file", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue)) session_.open(path_);
    if (!session_.load_error().empty()) error_text(session_.load_error());
    if (!session_.renderer()) {
      ImGui::End();
      return;
    }
    const SceneInfo& info = session_.renderer()->info();
    ImGui::TextUnformatted(info.description.c_str());
    figures();
    ViewSettings s = session_.settings();
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
    if (!session_.shown().error.empty()) error_text(session_.shown().error);
    ImGui::End();
    if (!(s == session_.settings())) {
      session_.settings() = s;
      session_.changed();
    }
  }

  static void error_text(const std::string& message) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
    ImGui::TextWrapped("%s", message.c_str());
    ImGui::PopStyleColor();
  }

  void figures() {
    const Published& shown = session_.shown();
    if (shown.frame->image.width == 0) {
      ImGui::TextUnformatted("rendering...");
      return;
    }
    const FrameSummary& f = session_.shown_summary();
    ImGui::Text("%dx%d (1/%d)  %.1f ms  %.2f Mrays/s", shown.frame->image.width, shown.frame->image.height,
                shown.factor, 1e3 * shown.seconds, shown.seconds > 0 ? 1e-6 * double(f.rays) / shown.seconds : 0.0);
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
    int borders = s.borders ? int(*s.borders) + 1 : 0;
    const char* border_modes[] = {"auto", "clip", "extend"};  // none, then BorderMode's order
    if (ImGui::Combo("borders", &borders, border_modes, 3))
      s.borders = borders == 0 ? std::nullopt : std::optional<BorderMode>(BorderMode(borders - 1));
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
    Orbit& orbit = session_.orbit();
    bool changed = ImGui::SliderFloat("azimuth", &orbit.azimuth, -180, 360, "%.1f");
    changed |= ImGui::SliderFloat("elevation", &orbit.elevation, -89.9f, 89.9f, "%.1f");
    changed |= ImGui::SliderFloat("fov", &orbit.fov, 1, 170, "%.1f");
    changed |= ImGui::SliderFloat("zoom", &orbit.zoom, 0.05f, 200, "%.3g", ImGuiSliderFlags_Logarithmic);
    if (changed) session_.moved();
    for (int k = 0; k < 6; ++k) {
      static const char* names[] = {"front", "right", "back", "left", "top", "bottom"};
      if (k) ImGui::SameLine();
      if (ImGui::SmallButton(names[k])) reset_view(k);
    }
    ImGui::InputText("camera file", camera_path_, sizeof camera_path_);
    if (ImGui::Button("save camera")) session_.save_camera(camera_path_);
    ImGui::SameLine();
    if (ImGui::Button("load camera")) session_.load_camera(camera_path_);
    ImGui::InputText("screenshot", shot_path_, sizeof shot_path_);
    if (ImGui::Button("save screenshot")) session_.ask_screenshot(shot_path_);
    if (!session_.message().empty()) ImGui::TextUnformatted(session_.message().c_str());
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
      failed_ = true;
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
  Session session_;
  FrameTexture texture_;
  std::string window_shot_;  // the script's `window` step: written once this frame is drawn
  bool failed_ = false;      // it could not be
  int frames_ = 0;
  bool key_down_[7] = {};
  char path_[1024] = {};
  char camera_path_[1024] = "camera.json";
  char shot_path_[1024] = "screenshot.png";
};

}  // namespace

bool has_window() { return true; }

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
