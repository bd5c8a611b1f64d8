// pss.estimate_h, pss.project, pss.render and pss.read_points: point clouds (paper §3, §5.2).
#pragma once

#include <pybind11/pybind11.h>

namespace pss::python {

void bind_points(pybind11::module_& module);

}  // namespace pss::python
