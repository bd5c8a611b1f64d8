// The viewer's render thread: renders the latest request at reduced resolution first (so
// that a frame takes at most ~50 ms while the camera moves), then at twice the resolution,
// and so on up to the full size; a newer request cancels the frame in progress (its CPU
// chunks not yet begun are skipped, core/cancel.hpp) and the levels still to come. The UI
// thread never waits on it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "pss/render/rendered_frame.hpp"
#include "scene.hpp"

namespace pss::app::view {

// The frame time the reduced levels aim at.
inline constexpr double kInteractiveSeconds = 0.05;

// The smallest power of two f ≤ 16 such that a frame that took `full_seconds` at full size
// takes at most kInteractiveSeconds at 1/f of the size each way; 4 before any (0). The time is
// the whole frame's as the window waits for it, not only its kernels: on a GPU at 1080p the
// copies back and the fresh host memory of the hits cost ten times the kernels (issue 29).
int reduction_for(double full_seconds);

struct Published {
  std::uint64_t request = 0;  // the request it answers
  int factor = 0;             // 1: full size
  // Shared, not copied: the window takes each publication, and a 1080p frame's hits are
  // 83 MB (the copy cost more than the GPU's render, issue 29). Never null once published.
  std::shared_ptr<const RenderedFrame> frame = std::make_shared<const RenderedFrame>();
  double seconds = 0;  // the frame's per-frame phases, as pss render counts them (the panel shows it)
  std::string error;   // what refused the request (a value out of range), frame untouched
};

class RenderThread {
 public:
  explicit RenderThread(std::unique_ptr<Scene> scene);
  ~RenderThread();
  RenderThread(const RenderThread&) = delete;
  RenderThread& operator=(const RenderThread&) = delete;

  const SceneInfo& info() const { return scene_info_; }
  Aabb bounds() const { return bounds_; }

  // Returns the request's number; the levels of earlier requests still to come are dropped.
  // The frames keep their per-pixel hits only at full size and only `with_hits` (what a
  // screenshot writes): a window just shows them, and at 1080p on a GPU the hits' copy back
  // is most of a frame's time (issue 29).
  std::uint64_t request(const Camera& camera, const ViewSettings& settings, bool with_hits);
  // Copies the newest publication into `out` when it is newer than `out` (by request and
  // level); returns whether it did.
  bool poll(Published& out) const;
  // Whether the full-size frame of request `id` (or a refusal of it) is published.
  bool finished(std::uint64_t id) const;

 private:
  void run();

  std::unique_ptr<Scene> scene_;
  SceneInfo scene_info_;
  Aabb bounds_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::atomic<bool> cancel_{false};  // set by a newer request, cleared when it is taken
  std::uint64_t next_id_ = 0;
  Camera camera_;
  ViewSettings settings_;
  bool with_hits_ = false;
  Published published_;
  std::uint64_t publications_ = 0;
  double full_seconds_ = 0;
  std::thread thread_;  // last: starts when everything above is ready
};

}  // namespace pss::app::view
