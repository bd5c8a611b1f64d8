#include "volume.hpp"

#include <cfloat>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "arrays.hpp"
#include "frame.hpp"
#include "interruptible.hpp"
#include "options.hpp"
#include "pss/core/error.hpp"
#include "pss/io/volume_file.hpp"
#include "pss/mesh/mesh_volume.hpp"
#include "pss/volume/extract.hpp"
#include "pss/volume/prepared.hpp"
#include "pss/volume/render_volume.hpp"

namespace pss::python {

namespace {

// pss.Volume: the values (owned, float32, x fastest, read-only from Python) and, when read
// from a file, its name, which the errors about the data then begin with, as the CLI's do.
struct PyVolume {
  Volume volume;
  std::string source;
  // The last preparation and its settings: a volume drawn from many views, or extracted
  // after it was drawn, is prepared once. The lock serialises the threads that share it.
  std::shared_ptr<const PreparedVolume> prepared;
  VolumeSettings prepared_for;
  std::unique_ptr<std::mutex> lock = std::make_unique<std::mutex>();
};

// Three positive numbers (sx, sy, sz): a spacing of 0 or below has no voxel size.
vec3 spacing_of(const py::handle& value) {
  const vec3 s = vec3_of(value, "spacing");
  if (!(s.x > 0 && s.y > 0 && s.z > 0)) throw Error("spacing: expected three positive numbers (sx, sy, sz)");
  return s;
}

PyVolume volume_of(const py::handle& values, const py::handle& spacing, const py::handle& origin) {
  const py::array any = py::array::ensure(values);
  // Complex numbers too: a cast would drop their imaginary parts with no more than a warning.
  const char kind = any ? any.dtype().kind() : 'O';
  if (!any || any.ndim() != 3 || kind == 'O' || kind == 'U' || kind == 'S' || kind == 'c')
    throw Error("values: expected a 3-D array of real numbers indexed [z, y, x] (got " +
                (any ? std::to_string(any.ndim()) + "-D " + std::string(py::str(any.dtype())) : shown(values)) + ")");
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(any);
  PyVolume v;
  v.volume.dims = ivec3(int(a.shape(2)), int(a.shape(1)), int(a.shape(0)));
  if (v.volume.dims.x < 1 || v.volume.dims.y < 1 || v.volume.dims.z < 1) throw Error("values: the array is empty");
  v.volume.values.assign(a.data(), a.data() + a.size());
  const auto nx = std::size_t(v.volume.dims.x), ny = std::size_t(v.volume.dims.y);
  for (std::size_t i = 0; i < v.volume.values.size(); ++i)
    if (!std::isfinite(v.volume.values[i]))  // named by its NumPy index [z, y, x]
      throw Error("values[" + std::to_string(i / (nx * ny)) + ", " + std::to_string(i / nx % ny) + ", " +
                  std::to_string(i % nx) + "] is not a finite number");
  v.volume.spacing = spacing_of(spacing);
  v.volume.origin = vec3_of(origin, "origin");
  return v;
}

VolumeSettings settings_of(const py::dict& o) {
  VolumeSettings s;
  s.gradient = flag(o, "gradient");
  if (is_given(o, "iso") == s.gradient) throw Error("choose the surface: iso=V or gradient=True");
  if (!s.gradient) s.iso = float(number_in(o, "iso", -FLT_MAX, FLT_MAX));
  s.method = choice(o, "method", {"predictor", "predictor-corrector"}) == "predictor" ? VolumeMethod::predictor
                                                                                : VolumeMethod::predictor_corrector;
  s.h = float(number_or(o, "h", s.h, kMinVolumeH, FLT_MAX));
  s.k = float(number_or(o, "k", s.k, kMinStepK, kMaxStepK));
  s.radius = float(number_or(o, "radius", s.radius, kMinRadius, kMaxRadius));
  s.alpha = float(number_or(o, "alpha", s.alpha, 0, 1));
  s.error = float(number_or(o, "error", s.error, 0, FLT_MAX, true));
  s.smoothing = float(number_or(o, "smoothing", s.smoothing, 0, FLT_MAX, true));
  if (is_given(o, "threshold")) {
    if (!s.gradient) throw Error("threshold applies to gradient surfaces only");
    s.threshold = float(number_in(o, "threshold", 0, 1));
  }
  validate(s);
  return s;
}

// f()'s result, its errors about the data naming the volume's file, as the CLI's do.
template <class F>
auto naming_source(const PyVolume& v, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    if (v.source.empty()) throw;
    throw file_error(v.source, e.what());
  }
}

// Gradients, weights, surface cells and bricks of a copy of the values (prepare_volume
// owns what it computes from), or the last ones when the settings are the same; the data's
// problems name the volume's file.
std::shared_ptr<const PreparedVolume> prepare(PyVolume& v, const VolumeSettings& settings, Stats& stats) {
  const std::lock_guard<std::mutex> hold(*v.lock);
  if (v.prepared && v.prepared_for == settings) return v.prepared;
  v.prepared.reset();  // its memory back before the next is made
  const auto prepared = naming_source(v, [&] {
    return std::make_shared<const PreparedVolume>(prepare_volume(Volume(v.volume), settings, stats));
  });
  const std::atomic<bool>* cancel = cancel_flag();
  if (cancel && cancel->load()) return prepared;  // cut short by Ctrl-C: not kept
  v.prepared = prepared;
  v.prepared_for = settings;
  return prepared;
}

py::object render(PyVolume& v, const py::dict& o) {
  const VolumeSettings settings = settings_of(o);
  const Backend backend = backend_of(o);
  const FrameRequest request = frame_request(o);
  Stats stats;
  RenderedFrame frame = run_interruptibly([&] {
    const std::shared_ptr<const PreparedVolume> prepared = prepare(v, settings, stats);
    const Camera camera = make_camera(request, prepared->surface_bounds(), glm::dvec3(0.0));
    const SceneMirror scene(backend, *prepared);
    return render_volume(scene, camera, trace_settings(request, camera), backend, stats);
  });
  stats.values()["backend"] = backend_name(backend);
  return frame_result(std::move(frame), stats, request);
}

py::object extract(PyVolume& v, const py::dict& o) {
  const VolumeSettings settings = settings_of(o);
  const Backend backend = backend_of(o);
  const bool full_output = flag(o, "full_output");
  Stats stats;
  ExtractionCounts counts;
  PointCloud cloud =
      run_interruptibly([&] { return extract_surface(*prepare(v, settings, stats), backend, stats, counts); });
  py::tuple points = py::make_tuple(to_numpy(std::move(cloud.positions)), to_numpy(std::move(cloud.normals)));
  if (!full_output) return points;
  stats.values()["candidates"] = counts.candidates;
  stats.values()["accepted"] = counts.accepted;
  stats.values()["points"] = counts.kept;
  stats.values()["backend"] = backend_name(backend);
  return py::make_tuple(points[0], points[1], stats_dict(stats));
}

// (vertices, normals, faces) of the volume's PSS, as `pss mesh` of a volume.
py::tuple mesh(PyVolume& v, const py::dict& o) {
  const VolumeSettings settings = settings_of(o);
  const std::optional<float> cell = positive_or_none(o, "cell");
  const Backend backend = backend_of(o);
  Stats stats;
  VolumeMesh result = run_interruptibly([&] {
    const std::shared_ptr<const PreparedVolume> prepared = prepare(v, settings, stats);
    return naming_source(v, [&] { return mesh_volume(*prepared, cell ? *cell : 0.0f, backend, stats); });
  });
  const auto t = py::ssize_t(result.mesh.triangles.size());
  return py::make_tuple(to_numpy(std::move(result.mesh.positions)), to_numpy(std::move(result.mesh.normals)),
                        to_numpy<std::int32_t>(std::move(result.mesh.triangles), {t, 3}));
}

// A headed file, or a raw one described by the arguments (as `pss volume`'s raw flags).
PyVolume read(const std::string& path, const py::dict& o) {
  std::optional<RawVolumeFormat> raw;
  if (is_given(o, "dims")) {
    const py::array dims = py::array::ensure(option(o, "dims"));
    if (!dims || dims.ndim() != 1 || dims.shape(0) != 3 || (dims.dtype().kind() != 'i' && dims.dtype().kind() != 'u'))
      throw Error("dims: expected (nx, ny, nz), three integers (got " + shown(option(o, "dims")) + ")");
    const auto d = py::array_t<long long, py::array::forcecast>::ensure(dims);
    RawVolumeFormat f;
    f.dims = parse_dims(std::to_string(d.at(0)) + "x" + std::to_string(d.at(1)) + "x" + std::to_string(d.at(2)));
    f.type = parse_voxel_type(text(o, "type"));
    if (is_given(o, "spacing")) f.spacing = spacing_of(option(o, "spacing"));
    f.big_endian = choice(o, "endian", {"little", "big"}) == "big";
    f.skip = integer_in(o, "skip", 0, INT32_MAX);
    raw = f;
  }
  PyVolume v;
  v.source = path;
  py::gil_scoped_release release;
  v.volume = read_volume(path, raw);
  return v;
}

py::array values_of(const py::object& self) {
  const Volume& v = self.cast<const PyVolume&>().volume;
  const auto f = py::ssize_t(sizeof(float));
  py::array a(py::dtype::of<float>(), {py::ssize_t(v.dims.z), py::ssize_t(v.dims.y), py::ssize_t(v.dims.x)},
              {f * v.dims.x * v.dims.y, f * v.dims.x, f}, v.values.data(), self);
  a.attr("setflags")(py::arg("write") = false);  // the volume's own values, viewed
  return a;
}

py::tuple triple(vec3 v) { return py::make_tuple(v.x, v.y, v.z); }

// pss.Volume(shape (z, y, x), spacing, origin[, source]): what the values are and where.
std::string repr(const PyVolume& v) {
  const Volume& volume = v.volume;
  std::string text = py::str("pss.Volume(shape={}, spacing={}, origin={}").format(
      py::make_tuple(volume.dims.z, volume.dims.y, volume.dims.x), triple(volume.spacing), triple(volume.origin));
  if (!v.source.empty()) text += ", source=" + py::repr(py::str(v.source)).cast<std::string>();
  return text + ")";
}

py::dict default_settings() {
  const VolumeSettings s;
  py::dict d;
  d["h"] = s.h;
  d["k"] = s.k;
  d["radius"] = s.radius;
  d["alpha"] = s.alpha;
  d["error"] = s.error;
  d["smoothing"] = s.smoothing;
  return d;
}

}  // namespace

void bind_volume(py::module_& m) {
  m.attr("volume_defaults") = default_settings();
  py::class_<PyVolume>(m, "Volume")
      .def(py::init(&volume_of), py::arg("values"), py::arg("spacing") = py::make_tuple(1, 1, 1),
           py::arg("origin") = py::make_tuple(0, 0, 0))
      .def_property_readonly("values", &values_of)
      .def_property_readonly("spacing", [](const PyVolume& v) { return triple(v.volume.spacing); })
      .def_property_readonly("origin", [](const PyVolume& v) { return triple(v.volume.origin); })
      .def_property_readonly("source", [](const PyVolume& v) { return v.source; })
      .def("__repr__", &repr)
      .def("_render", &render, py::arg("options"))  // with their signatures in __init__.py
      .def("_extract", &extract, py::arg("options"))
      .def("_mesh", &mesh, py::arg("options"));
  m.def("read_volume", &read, py::arg("path"), py::arg("options"));
}

}  // namespace pss::python
