// What a renderer writes: the image in the format its name says, --hits (the primary hits
// as a point cloud) and the frame's counts for --stats.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "pss/core/stats.hpp"
#include "pss/render/rendered_frame.hpp"

namespace pss {

// The counts of the frame's hits (its summary when they did not come back).
FrameSummary summarize(const RenderedFrame& frame);

// The hit's normal turned toward the camera, as a viewer sees the surface.
vec3 normal_facing_camera(const RenderedFrame& frame, std::size_t pixel);

// The image as 8-bit sRGB, row by row from the top: RGB, or with `transparent` RGBA with alpha
// 255 where the primary ray hit and 0 where it missed.
std::vector<std::uint8_t> frame_srgb8(const RenderedFrame& frame, bool transparent);

// JPEG quality of -o *.jpg: artefacts hard to see, a third of the PNG's size.
inline constexpr int kJpegQuality = 95;

// The image in the format of path's extension (image_format_of): PNG and JPEG in 8-bit sRGB;
// EXR as linear RGBA with Z, the primary ray's distance (+inf where it missed), and N.X N.Y
// N.Z, the normal facing the camera (0 where it missed). `transparent`: alpha 0 where the
// primary ray missed and 1 where it hit (a JPEG has no alpha: an error), else 1 throughout.
void write_frame_image(const std::filesystem::path& path, const RenderedFrame& frame, bool transparent);

// x y z nx ny nz for every pixel whose primary ray hit, normals facing the camera, as a point
// cloud in the format of path's extension (write_point_cloud); a PLY adds the pixel's px py.
void write_hits(const std::filesystem::path& path, const RenderedFrame& frame);

// Adds rays, hits, secondary rays, mean iterations, image size and camera to stats.values().
void record_frame(Stats& stats, const RenderedFrame& frame);

}  // namespace pss
