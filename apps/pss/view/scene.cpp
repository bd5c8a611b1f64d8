#include "scene.hpp"

#include <cmath>
#include <cstdio>

#include "pss/core/cancel.hpp"
#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/points/render_cloud.hpp"
#include "pss/volume/histogram.hpp"
#include "pss/volume/render_volume.hpp"

namespace pss::app::view {

namespace {

constexpr int kHistogramBins = 64;

class CloudScene : public Scene {
 public:
  CloudScene(const std::string& path, ViewSettings& settings) {
    cloud_ = read_point_cloud(path);
    if (cloud_.size() == 0) throw file_error(path, "has no points");
    try {
      info_.default_h = default_h(cloud_.positions);
    } catch (const Error& e) {
      throw file_error(path, e.what());
    }
    info_.description = std::to_string(cloud_.size()) + " points";
    info_.origin = cloud_.origin;
    if (settings.h == 0) settings.h = info_.default_h;
    if (settings.epsilon == 0) settings.epsilon = RayPssParams::from_h(settings.h).epsilon;
  }
  const SceneInfo& info() const override { return info_; }
  Aabb bounds() const override { return cloud_.bounds(); }

  RenderedFrame render(const ViewSettings& s, const Camera& camera, const std::atomic<bool>& cancel, Stats& stats,
                       FrameHits keep) override {
    RayPssParams params = RayPssParams::from_h(s.h);
    if (s.rho != 0) params.projection.rho = s.rho;
    params.projection.support = s.adaptive_support ? Support::adaptive : Support::global;
    params.projection.surface = s.surface;
    params.projection.normals = s.normals;
    params.projection.outliers = s.outliers;
    params.epsilon = s.epsilon;
    params.max_iterations = s.iterations;
    params.secondary = s.secondary_full ? SecondaryMode::full : SecondaryMode::paper;
    params.projection.borders = borders_for(s.borders, cloud_);
    validate(params);
    // APSS and RIMLS need the samples' normals, which a cloud prepared for MLS lacks; once
    // there, every operator renders from the same preparation.
    const bool needs_normals = s.surface != SurfaceOperator::mls &&
                               (!prepared_ || prepared_->normals_used() == NormalsUsed::none);
    if (!prepared_ || s.h != prepared_h_ || s.rho != prepared_rho_ || s.adaptive_support != prepared_adaptive_ ||
        s.backend != prepared_backend_ || needs_normals) {
      prepared_.reset();
      prepared_ = std::make_unique<PreparedCloud>(cloud_, params, s.backend, stats);
      prepared_h_ = s.h;
      prepared_rho_ = s.rho;
      prepared_adaptive_ = s.adaptive_support;
      prepared_backend_ = s.backend;
    }
    prepared_->set_search(params);
    const TraceSettings trace = TraceSettings::for_camera(camera, s.shadows, s.reflections);
    const CancelScope scope(&cancel);
    return render_cloud(*prepared_, camera, trace, s.backend, stats, keep);
  }

 private:
  PointCloud cloud_;
  SceneInfo info_;
  std::unique_ptr<PreparedCloud> prepared_;
  float prepared_h_ = 0, prepared_rho_ = 0;
  bool prepared_adaptive_ = true;
  Backend prepared_backend_ = Backend::cpu;
};

class VolumeScene : public Scene {
 public:
  VolumeScene(const VolumeOptions& o, ViewSettings& settings) {
    volume_ = read_volume(o.input, raw_volume_format(o.raw, o.input));
    const ValueStats values = value_stats(volume_.values);
    info_.is_volume = true;
    info_.description = std::to_string(volume_.dims.x) + "x" + std::to_string(volume_.dims.y) + "x" +
                        std::to_string(volume_.dims.z) + " voxels";
    info_.value_min = values.min;
    info_.value_max = values.max;
    const Histogram h = make_histogram(volume_.values, kHistogramBins, values.min, values.max);
    for (std::int64_t c : h.counts) info_.histogram.push_back(std::log1p(float(c)));
    // Without --iso or --gradient, the middle of the data's range.
    if (o.iso_option->count() == 0 && !settings.volume.gradient) settings.volume.iso = 0.5f * (values.min + values.max);
    Stats stats;
    prepare(settings, stats);
  }
  const SceneInfo& info() const override { return info_; }
  Aabb bounds() const override { return prepared_->surface_bounds(); }

  RenderedFrame render(const ViewSettings& s, const Camera& camera, const std::atomic<bool>& cancel, Stats& stats,
                       FrameHits keep) override {
    if (!(s.volume == prepared_settings_.volume) || s.backend != prepared_settings_.backend) prepare(s, stats);
    // The fields where the kernels run, made again only when they change: on a GPU a new
    // mirror is an upload of the whole volume (the engine's: 150 MB a frame, issue 29).
    if (!mirror_ || s.debug_projection != prepared_->params.debug_projection) {
      prepared_->params.debug_projection = s.debug_projection;
      mirror_.reset();
      mirror_ = std::make_unique<SceneMirror>(s.backend, *prepared_);
    }
    const TraceSettings trace = TraceSettings::for_camera(camera, s.shadows, s.reflections);
    const CancelScope scope(&cancel);
    // The Figure 2 view paints from the hits' flags.
    RenderedFrame frame = render_volume(*mirror_, camera, trace, s.backend, stats,
                                        s.debug_projection ? FrameHits::all : keep);
    if (s.debug_projection) paint_debug_projection(frame);
    return frame;
  }

 private:
  void prepare(const ViewSettings& s, Stats& stats) {
    auto next = std::make_unique<PreparedVolume>(prepare_volume(volume_, s.volume, stats));
    mirror_.reset();  // it points into the last preparation (on the CPU) or copies it (GPU)
    prepared_ = std::move(next);  // only once it succeeded: a refused iso leaves the last surface
    prepared_settings_ = s;
  }

  Volume volume_;
  SceneInfo info_;
  std::unique_ptr<PreparedVolume> prepared_;
  ViewSettings prepared_settings_;
  std::unique_ptr<SceneMirror> mirror_;  // of prepared_, where the kernels run; declared after it, gone before it
};

}  // namespace

std::unique_ptr<Scene> open_scene(const VolumeOptions& o, ViewSettings& settings) {
  const bool volume = has_volume_header(o.input) || raw_volume_format(o.raw, o.input).has_value();
  if (!volume) return std::make_unique<CloudScene>(o.input, settings);
  try {
    return std::make_unique<VolumeScene>(o, settings);
  } catch (const Error& e) {
    const std::string what = e.what();
    // The reader's messages name the file already; the preparation's do not.
    throw what.find(o.input) == std::string::npos ? file_error(o.input, what) : e;
  }
}

}  // namespace pss::app::view
