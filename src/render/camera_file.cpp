#include "pss/render/camera_file.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <system_error>

#include "pss/core/error.hpp"

namespace pss {

namespace {

constexpr std::uintmax_t kMaxBytes = 1 << 20;  // a stats file is a few KB
// The field of view that --fov allows, 1° to 170°.
const float kMinTanHalfFov = std::tan(0.5f * std::numbers::pi_v<float> / 180.0f);
const float kMaxTanHalfFov = std::tan(85.0f * std::numbers::pi_v<float> / 180.0f);

nlohmann::json vector_json(glm::dvec3 v) { return {v.x, v.y, v.z}; }

// Rounding of a camera that was orthonormal as floats: such a camera is used as it is.
constexpr float kOrthonormal = 1e-5f;
// cos 1°: how far a given "right" may lie off forward × up (a hand-written camera's rounding).
constexpr double kRightAgrees = 0.99985;

bool orthonormal(vec3 f, vec3 r, vec3 u) {
  auto unit = [](vec3 v) { return std::abs(glm::length(v) - 1.0f) < kOrthonormal; };
  return unit(f) && unit(r) && unit(u) && std::abs(glm::dot(f, r)) < kOrthonormal &&
         std::abs(glm::dot(f, u)) < kOrthonormal && std::abs(glm::dot(r, u)) < kOrthonormal &&
         glm::dot(glm::cross(r, u), -f) > 0;  // right-handed: right × up = backward
}

// The file's JSON document, bounded in size; whether it holds a camera is camera_from_json's.
nlohmann::json parsed_camera_file(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw file_error(path, "cannot read the camera file (" + ec.message() + ")");
  if (size > kMaxBytes) throw file_error(path, "is too large for a camera file (over 1 MiB)");
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw file_error(path, "cannot read the camera file");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {  // where the text stops being JSON
    throw file_error(path, "is not JSON (expected a camera): a syntax error at byte " + std::to_string(e.byte));
  }
}

}  // namespace

nlohmann::json camera_to_json(const Camera& c, const glm::dvec3& origin) {
  return {{"eye", vector_json(origin + glm::dvec3(c.eye))}, {"forward", vector_json(c.forward)},
          {"right", vector_json(c.right)}, {"up", vector_json(c.up)},
          {"tan_half_fov", c.tan_half_fov}};
}

Camera read_camera_file(const std::filesystem::path& path, int width, int height, const glm::dvec3& origin) {
  return camera_from_json(parsed_camera_file(path), width, height, path.string(), origin);
}

nlohmann::json read_camera_json(const std::filesystem::path& path) {
  nlohmann::json doc = parsed_camera_file(path);
  camera_from_json(doc, 1, 1, path.string(), glm::dvec3(0.0));  // throws for what is not a camera
  return doc;
}

Camera camera_from_json(const nlohmann::json& doc, int width, int height, const std::string& source,
                        const glm::dvec3& origin) {
  auto error = [&](const std::string& problem) { return file_error(source, problem); };
  if (!doc.is_object()) throw error("is not a JSON object (expected a camera)");
  const nlohmann::json& cam = doc.contains("camera") ? doc["camera"] : doc;
  if (!cam.is_object()) throw error("\"camera\" is not a JSON object");
  auto number = [&](const nlohmann::json& j, const std::string& name) {
    if (!j.is_number()) throw error("camera field \"" + name + "\" must be a number");
    const double x = j.get<double>();
    if (!std::isfinite(x) || std::abs(x) > 1e30) throw error("camera field \"" + name + "\" is out of range");
    return x;
  };
  auto vector = [&](const std::string& name) {
    if (!cam.contains(name)) throw error("camera field \"" + name + "\" is missing");
    const nlohmann::json& j = cam[name];
    if (!j.is_array() || j.size() != 3) throw error("camera field \"" + name + "\" must be [x, y, z]");
    return glm::dvec3(number(j[0], name), number(j[1], name), number(j[2], name));
  };
  Camera c;
  c.width = width;
  c.height = height;
  c.eye = vec3(vector("eye") - origin);
  const vec3 forward(vector("forward")), up(vector("up"));
  if (!cam.contains("tan_half_fov")) throw error("camera field \"tan_half_fov\" is missing");
  c.tan_half_fov = float(number(cam["tan_half_fov"], "tan_half_fov"));
  if (!(c.tan_half_fov >= kMinTanHalfFov && c.tan_half_fov <= kMaxTanHalfFov))
    throw error("camera field \"tan_half_fov\" must give a field of view from 1 to 170 degrees");
  const vec3 right = cam.contains("right") ? vec3(vector("right")) : glm::cross(forward, up);
  // "right" is forward × up, of any length: one that is not (a mirrored camera) is an error,
  // not a field read and then ignored.
  if (cam.contains("right")) {
    const glm::dvec3 derived = glm::cross(glm::dvec3(forward), glm::dvec3(up)), given(right);
    if (!(glm::dot(derived, given) > kRightAgrees * glm::length(derived) * glm::length(given)))
      throw error("camera field \"right\" must be forward x up (leave it out to have it so)");
  }
  if (orthonormal(forward, right, up)) {
    c.forward = forward;
    c.right = right;
    c.up = up;
    return c;
  }
  // Made orthonormal in double: the directions may be of any length, up need not be
  // perpendicular to forward, only not parallel to it.
  const glm::dvec3 f = glm::dvec3(forward), u = glm::dvec3(up);
  const glm::dvec3 r = glm::cross(f, u);
  if (!(glm::length(f) > 0) || !(glm::length(r) > 1e-6 * glm::length(f) * glm::length(u)))
    throw error("camera \"forward\" must be non-zero and \"up\" not parallel to it");
  c.forward = vec3(glm::normalize(f));
  c.right = vec3(glm::normalize(r));
  c.up = glm::cross(c.right, c.forward);
  return c;
}

}  // namespace pss
