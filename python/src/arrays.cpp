#include "arrays.hpp"

#include <cfloat>
#include <cmath>
#include <string>

#include "pss/core/error.hpp"

namespace pss::python {

namespace {

static_assert(sizeof(vec3) == 3 * sizeof(float) && sizeof(Rgb8) == 3, "rows are packed triples");

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

// Any array-like of numbers as C-ordered T, converted once; a one-line Error otherwise.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> numbers(const py::handle& value, const char* name) {
  const py::array any = py::array::ensure(value);
  // Complex numbers too: a cast would drop their imaginary parts with no more than a warning.
  const char kind = any ? any.dtype().kind() : 'O';
  if (kind == 'O' || kind == 'U' || kind == 'S' || kind == 'c')
    throw Error(std::string(name) + ": expected an array of real numbers");
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(any);
}

template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> rows_of_three(const py::handle& value, const char* name) {
  auto a = numbers<T>(value, name);
  if (!a) throw Error(std::string(name) + ": expected an array of real numbers");
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw Error(std::string(name) + ": expected an array of shape (N, 3) (got shape " + shape_text(a) + ")");
  return a;
}

}  // namespace

std::vector<glm::dvec3> world_rows(const py::handle& array, const char* name) {
  // Read as double: a value beyond float's range is refused rather than cast to inf, and a
  // georeferenced cloud keeps its digits until it is taken about its origin.
  const auto a = rows_of_three<double>(array, name);
  std::vector<glm::dvec3> out(std::size_t(a.shape(0)));
  const double* v = a.data();
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = v[3 * i + c];
      if (!(std::abs(x) <= FLT_MAX))
        throw Error(std::string(name) + ": row " + std::to_string(i) + " is not three finite numbers (that fit a float)");
      out[i][c] = x;
    }
  }
  return out;
}

std::vector<vec3> vec3_rows(const py::handle& array, const char* name) {
  const std::vector<glm::dvec3> rows = world_rows(array, name);
  return {rows.begin(), rows.end()};
}

PointCloud cloud_of_rows(const py::handle& array, const char* name) {
  PointCloud cloud;
  set_world_positions(cloud, world_rows(array, name));
  return cloud;
}

py::array world_numpy(std::vector<vec3>&& local, const glm::dvec3& origin, std::vector<py::ssize_t> shape) {
  if (origin == glm::dvec3(0.0)) return to_numpy<float>(std::move(local), std::move(shape));
  std::vector<glm::dvec3> world(local.size());
  for (std::size_t i = 0; i < local.size(); ++i) world[i] = origin + glm::dvec3(local[i]);
  return to_numpy<double>(std::move(world), std::move(shape));
}

std::vector<Rgb8> rgb8_rows(const py::handle& array, const char* name) {
  const py::array any = py::array::ensure(array);  // converted once, and its kind kept
  const bool floats = any && any.dtype().kind() == 'f';
  const auto a = rows_of_three<double>(any ? py::handle(any) : array, name);
  const double scale = floats ? 255.0 : 1.0;
  std::vector<Rgb8> out(std::size_t(a.shape(0)));
  const double* v = a.data();
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = v[3 * i + c] * scale;
      if (!(x >= 0 && x <= 255.5))
        throw Error(std::string(name) + ": row " + std::to_string(i) + " is not a colour (" +
                    (floats ? "floats from 0 to 1" : "integers from 0 to 255") + ")");
      out[i][c] = std::uint8_t(std::lround(std::min(x, 255.0)));
    }
  return out;
}

glm::dvec3 dvec3_of(const py::handle& value, const char* name) {
  const auto a = numbers<double>(value, name);
  if (a.ndim() != 1 || a.shape(0) != 3)
    throw Error(std::string(name) + ": expected three numbers (got shape " + shape_text(a) + ")");
  const glm::dvec3 v(a.at(0), a.at(1), a.at(2));
  // Finite as floats too: the library computes in float.
  if (!(std::abs(v.x) <= FLT_MAX && std::abs(v.y) <= FLT_MAX && std::abs(v.z) <= FLT_MAX))
    throw Error(std::string(name) + ": expected three finite numbers");
  return v;
}

vec3 vec3_of(const py::handle& value, const char* name) { return vec3(dvec3_of(value, name)); }

}  // namespace pss::python
