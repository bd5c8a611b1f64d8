// A camera as JSON, so that a view found in one run (or in `pss view`) renders again
// exactly: {"eye": [x, y, z], "forward": [...], "right": [...], "up": [...],
// "tan_half_fov": t}, the object `--stats` writes under "camera". The eye is in world
// coordinates, in double: a camera moves between clouds taken about different origins
// (points/cloud.hpp), for which the camera itself is relative to `origin`.
#pragma once

#include <filesystem>
#include <string>

#include <glm/ext/vector_double3.hpp>
#include <nlohmann/json.hpp>

#include "pss/render/camera.hpp"

namespace pss {

nlohmann::json camera_to_json(const Camera& camera, const glm::dvec3& origin);

// The camera of a JSON file: a camera object, or an object holding one under "camera" (a
// --stats file loads as it is). "right" may be left out (it is forward × up). A camera
// pss wrote loads bit for bit; another is made orthonormal (forward kept, up in the plane
// of forward and up). The image size is the caller's. Throws Error naming the file for
// what is not such a camera (bounded: a camera file over 1 MiB is refused unread).
Camera read_camera_file(const std::filesystem::path& path, int width, int height, const glm::dvec3& origin);

// The file's document, checked to hold such a camera: for a caller that places it later
// (camera_from_json), about an origin not yet known.
nlohmann::json read_camera_json(const std::filesystem::path& path);

// The same from a parsed document; errors name `source` (the file, or where the JSON came from).
Camera camera_from_json(const nlohmann::json& doc, int width, int height, const std::string& source,
                        const glm::dvec3& origin);

}  // namespace pss
