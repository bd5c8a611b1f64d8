// Rendering the PSS of a volume (§5.1) through the shared render pipeline
// (render/rendered_frame.hpp): the volume's surface finder marches each ray (marcher.hpp);
// shading, secondary rays, --hits and --stats are those of `pss render`.
#pragma once

#include <cstdint>

#include "pss/backend/backend.hpp"
#include "pss/render/rendered_frame.hpp"
#include "pss/volume/marcher.hpp"
#include "pss/volume/prepared.hpp"

namespace pss {

// The Finder of render/trace.hpp for a volume.
struct VolumeFinder {
  static constexpr bool kTiledRays = true;  // frame_kernels.hpp: measured faster for volumes
  VolumeScene scene;

  PSS_HOST_DEVICE Hit primary(const Ray& ray) const { return march_volume(scene, ray); }
  PSS_HOST_DEVICE Hit secondary(const Ray& ray, float t_max) const { return march_volume(scene, ray, t_max); }
  // Samples within b of the surface pass the fragment test; from 1.5·b away the surface
  // just left projects outside the ball of trust and is not found again.
  PSS_HOST_DEVICE float secondary_offset(const Hit&) const { return 1.5f * scene.params.step; }
  PSS_HOST_DEVICE vec3 albedo(const Hit&, vec3 base) const { return base; }  // a volume has one colour
};

// The scene's arrays where the kernels run: make the SceneMirror once to draw many frames
// (on the GPU it is the upload of the volume's fields).
RenderedFrame render_volume(const SceneMirror& scene, const Camera& camera, const TraceSettings& settings,
                            Backend backend, Stats& stats, FrameHits keep = FrameHits::all);
RenderedFrame render_volume(const PreparedVolume& volume, const Camera& camera, const TraceSettings& settings,
                            Backend backend, Stats& stats);

// --debug-projection: pixels whose first projection the predictor moved farther than ε
// red, those the corrector still moved farther than ε green, both keeping the shading's
// brightness so that the shape stays readable.
void paint_debug_projection(RenderedFrame& frame);

}  // namespace pss
