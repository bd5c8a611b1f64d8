// NumPy arrays in and out of the library's types. Inputs are checked and converted once
// (float32, C order: the grid reorders the points anyway, and a volume's gradients are
// computed from a copy it owns); outputs hand the library's vectors to NumPy without a copy.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "pss/core/types.hpp"
#include "pss/points/cloud.hpp"

namespace pss::python {

namespace py = pybind11;

// An (N, 3) array of finite numbers as points; a one-line pss::Error naming `name` otherwise.
std::vector<glm::dvec3> world_rows(const py::handle& array, const char* name);
// The same as floats (normals).
std::vector<vec3> vec3_rows(const py::handle& array, const char* name);
// The same as a cloud's positions about its origin (cloud.hpp: set_world_positions).
PointCloud cloud_of_rows(const py::handle& array, const char* name);

// An (N, 3) array of colours, 0..255 integers or 0..1 floats, as 8-bit sRGB.
std::vector<Rgb8> rgb8_rows(const py::handle& array, const char* name);

// Three finite numbers (a tuple, list or array); dvec3_of keeps them in double (a world
// point far from zero).
glm::dvec3 dvec3_of(const py::handle& value, const char* name);
vec3 vec3_of(const py::handle& value, const char* name);

// `data` moved into a NumPy array of `shape` (whose product is the element count of
// Element's scalars); the array owns it.
template <class Scalar, class Element>
py::array_t<Scalar> to_numpy(std::vector<Element>&& data, std::vector<py::ssize_t> shape) {
  static_assert(sizeof(Element) % sizeof(Scalar) == 0);
  auto* owned = new std::vector<Element>(std::move(data));
  const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<Element>*>(p); });
  return py::array_t<Scalar>(std::move(shape), reinterpret_cast<const Scalar*>(owned->data()), owner);
}

// Points relative to `origin` as world positions: float32 where the origin is zero, else
// float64 (the digits a georeferenced cloud needs).
py::array world_numpy(std::vector<vec3>&& local, const glm::dvec3& origin, std::vector<py::ssize_t> shape);

// Points (N, 3) float32, colours (N, 3) uint8.
inline py::array_t<float> to_numpy(std::vector<vec3>&& v) {
  const auto n = py::ssize_t(v.size());
  return to_numpy<float>(std::move(v), {n, 3});
}
inline py::array_t<std::uint8_t> to_numpy(std::vector<Rgb8>&& v) {
  const auto n = py::ssize_t(v.size());
  return to_numpy<std::uint8_t>(std::move(v), {n, 3});
}

}  // namespace pss::python
