// A scripted viewer session (`pss view FILE --script STEPS --screenshot-dir DIR`): what a
// user does, one step a line, so that the viewer runs unattended, in a window (the tests run
// it under Xvfb) or with --headless, and its screenshots can be compared with the batch
// commands. '#' starts a comment.
//   view AZ EL           orbit to azimuth and elevation (degrees)
//   zoom Z | pan X Y | fov DEG
//   camera FILE.json     the camera of a file (--camera's format), until the next move
//   set NAME VALUE       a panel value: h, rho, support (adaptive|global), surface
//                        (mls|apss|rimls), epsilon,
//                        iterations, secondary (full|paper), borders (auto|clip|extend),
//                        shadows, reflections, debug (on|off), iso, threshold, gradient
//                        (on|off), method (predictor|predictor-corrector)
//   wait                 until the full-size frame of the current view is drawn
//   screenshot NAME      wait, then write DIR/NAME.png, DIR/NAME.json (camera, counts: as
//                        --stats) and DIR/NAME.ply (the primary hits: as --hits)
//   window NAME          wait, then write the whole window, panel included, to DIR/NAME.png
//                        (refused with --headless, which has no window)
//   quit                 (implied after the last step)
#pragma once

#include <string>
#include <vector>

namespace pss::app::view {

struct Step {
  std::string verb;
  std::vector<std::string> args;
  int line = 0;
};

// Throws Error "FILE:LINE: ..." for an unknown step or a wrong number of arguments.
std::vector<Step> read_script(const std::string& path);

}  // namespace pss::app::view
