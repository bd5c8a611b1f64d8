// pss.Volume (render, extract) and pss.read_volume: the PSS of a volume (paper §4, §5.1).
#pragma once

#include <pybind11/pybind11.h>

namespace pss::python {

void bind_volume(pybind11::module_& module);

}  // namespace pss::python
