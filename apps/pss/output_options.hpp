// The output flags' check of the file's extension (pss/io/output_format.hpp): done while
// parsing, so `-o img.gif` or `--hits h.png` is a one-line usage error naming the flag and
// the file before any work.
#pragma once

#include <CLI/CLI.hpp>

namespace pss::app {

CLI::Validator image_output();   // .png, .jpg, .jpeg, .exr
CLI::Validator points_output();  // .ply, .xyz
CLI::Validator mesh_output();    // .ply, .obj, .stl, .off

}  // namespace pss::app
