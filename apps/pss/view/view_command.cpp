// pss view FILE: the interactive viewer's flags (viewer.hpp).
#include "view_command.hpp"

#include <cstdio>
#include <cstdlib>

#include "commands.hpp"
#include "numbers.hpp"
#include "pss/core/progress.hpp"
#include "pss/core/text.hpp"
#include "viewer.hpp"

namespace pss::app {

void add_view_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "view", view::has_window() ? "Explore the PSS of a point cloud or a volume in a window (or run a script of views with "
                                 "--headless)"
                               : "Run a script of views of the PSS of a point cloud or a volume (this build has no "
                                 "window: --headless only)");
  auto o = std::make_shared<view::ViewerOptions>();
  add_volume_options(*command, o->file, true);
  command->get_option("file")->description(
      "point cloud (.ply, .xyz/.txt/.pts, .obj, .stl, .pcd, .las) or volume (.nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, or raw with --dims and "
      "--type)");
  // --h means a cloud's own units too: the volume bound (at least 0.5 voxels) is checked
  // when a volume opens (VolumeSettings), here only that it is a positive number.
  CLI::Option* h = command->get_option("--h");
  h->get_validator(0)->active(false);
  h->check(finite_positive());
  h->description("h: for a volume in voxels (default 2, at least 0.5); for a point cloud in its units (default: from "
                 "the spacing)");
  auto* size = command->add_option_function<std::string>(
      "--size",
      [o](const std::string& text) {
        const auto x = text.find('x');
        o->width = std::stoi(text.substr(0, x));
        o->height = std::stoi(text.substr(x + 1));
      },
      "window size WIDTHxHEIGHT (default 960x720): the full-size frame");
  size->check(CLI::Validator(
      [](std::string& t) -> std::string {
        const auto x = t.find('x');
        int w = 0, h = 0;
        if (x == std::string::npos || std::sscanf(t.c_str(), "%dx%d", &w, &h) != 2 || w < 64 || h < 64 || w > 8192 ||
            h > 8192)
          return "expected WIDTHxHEIGHT, each from 64 to 8192 (got " + quote(t) + ")";
        return {};
      },
      "WxH", "size"));
  command->add_option("--camera", o->camera_file, "the first view: a camera JSON file (as pss render --camera)");
  command->add_flag("--shadows", o->settings.shadows, "shadow rays toward the key light");
  command->add_flag("--reflections", o->settings.reflections, "one mirror reflection per primary hit");
  auto support = std::make_shared<std::string>();
  add_support_option(*command, *support);
  auto surface = std::make_shared<SurfaceOptions>();
  add_surface_options(*command, *surface);
  command->add_option("--script", o->script, "run these steps (one a line: view, zoom, set, wait, screenshot, ...), then quit");
  command->add_option("--screenshot-dir", o->screenshot_dir, "where the script's screenshots go (default .)");
  command->add_flag("--headless", o->headless,
                    "no window: run --script's steps with the same frames, screenshots and timings (for a machine "
                    "without a display, such as a GPU server)");
  auto backend = std::make_shared<std::string>("auto");
  command->add_option("--backend", *backend, "cpu, cuda, or auto")->check(CLI::IsMember({"cpu", "cuda", "auto"}));
  const CLI::Option* h_option = command->get_option("--h");
  command->callback([o, backend, support, surface, h_option] {
    o->settings.backend = select_backend(*backend);
    o->settings.volume = o->file.settings;
    o->settings.volume.method =
        o->file.method == "predictor" ? VolumeMethod::predictor : VolumeMethod::predictor_corrector;
    // For a point cloud --h is in its own units (0: estimated); the volume default is 2 voxels.
    o->settings.h = h_option->count() ? o->file.settings.h : 0;
    o->settings.adaptive_support = support_of(*support, h_option->count() > 0) == Support::adaptive;
    ProjectionParams chosen;
    apply_surface_options(*surface, chosen);
    o->settings.surface = chosen.surface;
    o->settings.normals = chosen.normals;
    o->settings.outliers = chosen.outliers;
    // The window shows each frame's progress; bars on the terminal behind it would only flicker.
    set_progress_mode(ProgressMode::never);
    if (const int status = o->headless ? view::run_headless(*o) : view::run_viewer(*o); status != 0) std::exit(status);
  });
}

}  // namespace pss::app
