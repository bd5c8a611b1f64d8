#include "pss/volume/render_volume.hpp"

#include "pss/render/render_frame.hpp"

namespace pss {

RenderedFrame render_volume(const SceneMirror& scene, const Camera& camera, const TraceSettings& settings,
                            Backend backend, Stats& stats, FrameHits keep) {
  return render_frame(backend, VolumeFinder{scene.scene()}, camera, settings, stats, keep);
}

RenderedFrame render_volume(const PreparedVolume& volume, const Camera& camera, const TraceSettings& settings,
                            Backend backend, Stats& stats) {
  return render_volume(SceneMirror(backend, volume), camera, settings, backend, stats);
}

void paint_debug_projection(RenderedFrame& frame) {
  for (std::size_t i = 0; i < frame.hits.size(); ++i) {
    const std::uint32_t flags = frame.hits[i].flags;
    if (!frame.hits[i].found() || !(flags & (kHitPredictorMoved | kHitCorrectorMoved))) continue;
    vec3& pixel = frame.image.pixels[i];
    const float brightness = 0.35f + 0.65f * glm::dot(pixel, vec3(0.2126f, 0.7152f, 0.0722f));
    pixel = brightness * ((flags & kHitCorrectorMoved) ? vec3(0.1f, 1.0f, 0.1f) : vec3(1.0f, 0.08f, 0.05f));
  }
}

}  // namespace pss
