// Which border mode a cloud gets when none is chosen (`--borders auto` of render, view and
// mesh; points/borders.hpp).
#pragma once

#include <optional>
#include <string_view>

#include "pss/points/cloud.hpp"
#include "pss/points/projection.hpp"

namespace pss {

// `--borders auto|clip|extend` (points/borders.hpp); auto is no choice (nullopt): a mesh's
// vertices are clipped, their surface ending at them, and a scan's surface extends past its
// last points, which stand for the surface around them (its border is where the scanner
// stopped, not where the object ends). A name it does not give is auto (callers check it).
inline std::optional<BorderMode> border_choice_of(std::string_view name) {
  if (name == "clip") return BorderMode::clip;
  if (name == "extend") return BorderMode::extend;
  return std::nullopt;
}
inline BorderMode borders_for(std::optional<BorderMode> choice, const PointCloud& cloud) {
  return choice.value_or(cloud.mesh_vertices ? BorderMode::clip : BorderMode::extend);
}

}  // namespace pss
