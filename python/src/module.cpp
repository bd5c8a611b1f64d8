// The extension module pss._pss under the Python package pss (python/pss/__init__.py, which
// gives the functions their keyword signatures and documentation).
#include <pybind11/pybind11.h>

#include "options.hpp"
#include "pss/backend/backend.hpp"
#include "points.hpp"
#include "pss/core/error.hpp"
#include "pss/core/progress.hpp"
#include "pss/render/camera.hpp"
#include "pss/render/shading.hpp"
#include "volume.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_pss, m) {
  m.doc() = "pss: point set surfaces of point clouds and volumes (C++ core)";
  // Every problem pss reports, with the CLI's one-line message: a ValueError.
  static const py::exception<pss::Error> error(m, "Error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const pss::Error& e) {
      PyErr_SetString(error.ptr(), pss::python::argument_names(e.what()).c_str());
    }
  });
  // A library call prints nothing unless asked to (pss.set_progress).
  pss::set_progress_mode(pss::ProgressMode::never);
  m.def("set_progress", [](const std::string& mode) {
    if (mode == "auto") pss::set_progress_mode(pss::ProgressMode::automatic);
    else if (mode == "always") pss::set_progress_mode(pss::ProgressMode::always);
    else if (mode == "never") pss::set_progress_mode(pss::ProgressMode::never);
    else throw pss::Error("progress: expected 'auto', 'always' or 'never' (got '" + mode + "')");
  });
  const pss::CameraSettings camera;
  m.attr("frame_defaults") = py::dict(py::arg("size") = py::make_tuple(camera.width, camera.height),
                                      py::arg("fov") = camera.fov_deg,
                                      py::arg("reflectivity") = pss::ShadingParams{}.reflectivity);
  m.def("set_threads", [](int threads) {
    if (threads < 0 || threads > pss::kMaxCpuThreads)
      throw pss::Error("threads: expected a count from 0 (every core) to " + std::to_string(pss::kMaxCpuThreads));
    pss::set_cpu_threads(threads);
  });
  pss::python::bind_points(m);
  pss::python::bind_volume(m);
}
