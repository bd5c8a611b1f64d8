// A viewer session without its window: the scene on its render thread, the panel's settings
// and the orbit, the newest frame shown, and the script's steps. The window (viewer.cpp)
// draws it and feeds it the user's input; --headless (headless.cpp) runs it alone, where
// there is no display (a GPU server), with the same frames, screenshots and timings.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "orbit.hpp"
#include "render_thread.hpp"
#include "script.hpp"
#include "viewer.hpp"

namespace pss::app::view {

class Session {
 public:
  // `write_window(png)` writes the window with its panel (the script's `window` step); a
  // session without one refuses that step. Opens options.file.input.
  Session(const ViewerOptions& options, std::vector<Step> steps, std::optional<nlohmann::json> camera,
          std::function<void(const std::string&)> write_window);

  // Opens another file; a failure leaves no scene and its message in load_error().
  void open(const std::string& path);
  // Sends a request for frames of `size` when something changed since the last, and takes
  // the newest frame; returns whether a new one came.
  bool update(glm::ivec2 size);
  // One step of the script when its time has come (`ready`: the window has laid itself out);
  // writes a screenshot asked for from the panel once its frame is there. Returns false once
  // the script has ended or a step failed (status() 1).
  bool run_script(bool ready);

  // What the panel and the input change; each change must be followed by changed() or moved().
  ViewSettings& settings() { return settings_; }
  Orbit& orbit() { return orbit_; }
  void changed() { dirty_ = true; }
  void moved();  // the orbit changed: a camera file's view is left
  void save_camera(const std::string& path);
  void load_camera(const std::string& path);
  void ask_screenshot(const std::string& path) { pending_shot_ = path; }

  const RenderThread* renderer() const { return renderer_.get(); }
  const Published& shown() const { return shown_; }
  const FrameSummary& shown_summary() const { return shown_summary_; }  // of shown().frame, counted once
  const std::string& load_error() const { return load_error_; }
  const std::string& message() const { return message_; }  // of the last camera or screenshot action
  int status() const { return status_; }

 private:
  glm::dvec3 origin() const;
  Camera camera() const;
  bool full_frame_shown() const;
  bool shot_ready();
  void write_screenshot(const std::string& image);
  void report_timing();
  void step(const Step& s);

  const ViewerOptions& o_;
  std::function<void(const std::string&)> write_window_;
  ViewSettings settings_;
  Orbit orbit_;
  std::optional<nlohmann::json> fixed_camera_;  // a camera file's (render/camera_file.hpp)
  std::unique_ptr<RenderThread> renderer_;
  glm::ivec2 size_{1};
  std::uint64_t request_ = 0;
  bool dirty_ = false;
  bool with_hits_ = false;  // the next requests keep their full frame's hits, for a screenshot
  Published shown_;
  FrameSummary shown_summary_;
  std::string load_error_, last_error_, message_, pending_shot_;
  std::vector<Step> steps_;
  std::size_t next_step_ = 0;
  int status_ = 0;
  // With --script, the timing of the current request (report_timing), unless it was a
  // screenshot's second render of the view.
  bool timed_ = true;
  std::chrono::steady_clock::time_point requested_at_;
  int first_shown_ = 0;
  double first_seconds_ = 0, first_frame_seconds_ = 0;
};

}  // namespace pss::app::view
