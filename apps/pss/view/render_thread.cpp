#include "render_thread.hpp"

#include <algorithm>
#include <chrono>

#include "pss/core/error.hpp"
#include "render_options.hpp"

namespace pss::app::view {

int reduction_for(double full_seconds) {
  if (!(full_seconds > 0)) return 4;
  int f = 1;
  while (f < 16 && full_seconds / double(f * f) > kInteractiveSeconds) f *= 2;
  return f;
}

RenderThread::RenderThread(std::unique_ptr<Scene> scene)
    : scene_(std::move(scene)), scene_info_(scene_->info()), bounds_(scene_->bounds()), thread_([this] { run(); }) {}

RenderThread::~RenderThread() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t RenderThread::request(const Camera& camera, const ViewSettings& settings, bool with_hits) {
  std::uint64_t id;
  {
    std::lock_guard lock(mutex_);
    id = ++next_id_;
    cancel_ = true;
    camera_ = camera;
    settings_ = settings;
    with_hits_ = with_hits;
  }
  wake_.notify_all();
  return id;
}

bool RenderThread::poll(Published& out) const {
  std::lock_guard lock(mutex_);
  if (published_.request == out.request && published_.factor == out.factor && published_.error == out.error)
    return false;
  if (publications_ == 0) return false;
  out = published_;
  return true;
}

bool RenderThread::finished(std::uint64_t id) const {
  std::lock_guard lock(mutex_);
  return published_.request == id && (published_.factor == 1 || !published_.error.empty());
}

void RenderThread::run() {
  std::uint64_t done = 0;
  for (;;) {
    Camera camera;
    ViewSettings settings;
    std::uint64_t id;
    double full_seconds;
    bool with_hits;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || next_id_ != done; });
      if (stop_) return;
      id = done = next_id_;
      cancel_ = false;
      camera = camera_;
      settings = settings_;
      with_hits = with_hits_;
      full_seconds = full_seconds_;
    }
    for (int factor = reduction_for(full_seconds); factor >= 1; factor /= 2) {
      Published p;
      p.request = id;
      p.factor = factor;
      double wall = 0;  // what the user waits for: the kernels, and the copies and allocations around them
      try {
        Stats stats;
        const auto start = std::chrono::steady_clock::now();
        const FrameHits keep = factor == 1 && with_hits ? FrameHits::all : FrameHits::summary;
        p.frame = std::make_shared<const RenderedFrame>(scene_->render(settings, camera.reduced(factor), cancel_, stats, keep));
        wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        p.seconds = frame_seconds(stats);
      } catch (const Error& e) {
        p.error = one_line(e.what());
      } catch (const std::bad_alloc&) {
        p.error = "out of memory";
      }
      std::lock_guard lock(mutex_);
      if (next_id_ != id && p.error.empty()) break;  // cancelled: its pixels are not all drawn
      // The time of a frame that only shows (a screenshot's, with its hits, would overstate it).
      if (factor == 1 && p.error.empty() && !with_hits) full_seconds_ = wall;
      const bool refused = !p.error.empty();
      if (refused) {  // keep showing the last image, with its figures
        p.frame = published_.frame;
        p.factor = published_.factor;
        p.seconds = published_.seconds;
      }
      published_ = std::move(p);
      ++publications_;
      if (refused) break;
    }
  }
}

}  // namespace pss::app::view
