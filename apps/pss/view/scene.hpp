// What `pss view` shows: a point cloud's or a volume's PSS, prepared once per data set and
// once per change of a parameter that the preparation depends on (h for a cloud; the
// surface for a volume), and rendered by the same library calls as `pss render` and
// `pss volume`. Scenes live on the viewer's render thread only.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/ext/vector_double3.hpp>

#include "pss/backend/backend.hpp"
#include "pss/core/stats.hpp"
#include "pss/points/projection.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/rendered_frame.hpp"
#include "pss/render/trace.hpp"
#include "volume_options.hpp"

namespace pss::app::view {

// Everything the panel can change. A render request carries a copy, so the render thread
// never reads what the UI thread is writing.
struct ViewSettings {
  // Both kinds.
  bool shadows = false;
  bool reflections = false;
  Backend backend = Backend::cpu;
  // Point clouds (0: the defaults of `pss render`).
  float h = 0;
  float rho = 0;  // the projection's range-query radius (0: 2h)
  bool adaptive_support = true;  // each sample's width from its spacing (points/support.hpp)
  SurfaceOperator surface = SurfaceOperator::rimls;  // --surface (points/projection.hpp)
  NormalSource normals = NormalSource::file;       // --normals
  OutlierPolicy outliers = OutlierPolicy::set_aside;  // --outliers
  float epsilon = 0;
  int iterations = 2;
  bool secondary_full = true;
  std::optional<BorderMode> borders;  // as render's --borders: clip, extend, or (none) auto
  // Volumes: the flags of `pss volume`.
  VolumeSettings volume;
  bool debug_projection = false;  // the paper's Figure 2

  bool operator==(const ViewSettings&) const = default;
};

// What the panel shows of the data.
struct SceneInfo {
  bool is_volume = false;
  std::string description;            // "35947 points" or "256x256x128 voxels"
  float value_min = 0, value_max = 0;  // volumes: the data's range (the iso slider's)
  std::vector<float> histogram;        // volumes: counts per bin, log scale
  float default_h = 0;                 // clouds: the h that pss render would choose
  glm::dvec3 origin{0.0};              // clouds: the world position of their zero (points/cloud.hpp)
};

class Scene {
 public:
  virtual ~Scene() = default;
  virtual const SceneInfo& info() const = 0;
  // The box the default camera frames (its surface, for volumes).
  virtual Aabb bounds() const = 0;
  // Re-prepares what `settings` changed since the last call, then renders; once `cancel` is
  // set the frame is abandoned (its pixels are not all drawn), the preparation never is.
  // `keep` says whether the per-pixel hits come back (a volume's Figure 2 view keeps them
  // always: it paints from them). Throws Error for a setting out of range, with the scene
  // left as it was.
  virtual RenderedFrame render(const ViewSettings& settings, const Camera& camera, const std::atomic<bool>& cancel,
                               Stats& stats, FrameHits keep) = 0;
};

// Reads the file (a volume when it has a volume header or raw flags are given) and prepares
// it with `settings`; throws Error naming the file.
std::unique_ptr<Scene> open_scene(const VolumeOptions& file, ViewSettings& settings);

}  // namespace pss::app::view
