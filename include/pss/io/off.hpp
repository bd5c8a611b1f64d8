// OFF meshes (Geomview's Object File Format, Princeton's shape benchmark, CGAL) as point
// clouds: the vertices, with the normals and colours the file gives them.
#pragma once

#include <filesystem>

#include "pss/points/cloud.hpp"

namespace pss {

// Reads the header keyword [ST][C][N]OFF (optional; 4OFF and nOFF, other dimensions, are
// refused), the counts `vertices faces edges` (on the keyword's line or the next), then one
// vertex per line: `x y z`, then `nx ny nz` with N, `r g b [a]` with C (integers 0..255, or
// 0..1 when written with a point or an exponent), `s t` with ST. Faces are not read. '#'
// starts a comment. Every problem is a one-line pss::Error "FILE: ...", with the line where
// there is one ("FILE: line N: ...").
PointCloud read_off(const std::filesystem::path& path);

}  // namespace pss
