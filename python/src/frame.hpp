// What pss.render and pss.Volume.render share: the camera and shading from their keyword
// arguments (the CLI's --size, --view, --fov, --look-at, --up, --distance, --zoom, --roll,
// --camera, --shadows, --reflections, --reflectivity, --transparent), and the frame handed to
// NumPy.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "pss/core/stats.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/rendered_frame.hpp"

namespace pss::python {

namespace py = pybind11;

struct FrameRequest {
  CameraSettings camera;
  std::optional<nlohmann::json> camera_json;  // a camera object, as --stats writes it
  std::string camera_file;                    // or a file holding one
  bool shadows = false, reflections = false, transparent = false, full_output = false;
  float reflectivity = 0;
};

// Reads and checks the arguments (before any work).
FrameRequest frame_request(const py::dict& options);

// The camera framing `bounds` (or the one given), and its shading; without the GIL. look_at
// and a given camera's eye are world coordinates, bounds and the result relative to `origin`
// (a cloud's, points/cloud.hpp).
Camera make_camera(const FrameRequest& request, const Aabb& bounds, const glm::dvec3& origin);
TraceSettings trace_settings(const FrameRequest& request, const Camera& camera);

// The (H, W, 3) or, transparent, (H, W, 4) uint8 image, with a RuntimeWarning when no ray
// hit; with full_output the tuple
// (image, hits, stats): hits a dict of (H, W) arrays 'mask', 'depth' (inf where missed),
// 'iterations' and (H, W, 3) 'points' (NaN where missed) and 'normals' (facing the camera,
// 0 where missed); stats the dict --stats writes.
py::object frame_result(RenderedFrame&& frame, Stats& stats, const FrameRequest& request);

// A pss::Stats as a Python dict.
py::dict stats_dict(const Stats& stats);

}  // namespace pss::python
