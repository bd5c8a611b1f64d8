// `pss view --headless`: the viewer's session driven by its script alone, for machines with
// no display (a GPU server): issue 29's viewer on the GPU, frames timed and saved.
#include <chrono>
#include <cstdio>
#include <thread>

#include "pss/core/error.hpp"
#include "pss/core/text.hpp"
#include "pss/render/camera_file.hpp"
#include "session.hpp"

namespace pss::app::view {

int run_headless(const ViewerOptions& options) {
  try {
    if (options.script.empty()) throw Error("--headless needs --script: the steps to run");
    std::vector<Step> steps = read_script(options.script);
    std::optional<nlohmann::json> camera;
    if (!options.camera_file.empty()) camera = read_camera_json(options.camera_file);
    Session session(options, std::move(steps), std::move(camera), nullptr);
    if (!session.renderer()) return 1;  // the file's message is on stderr
    // The window's loop without the window: take frames as they come, a step when its time has
    // come; a millisecond's sleep keeps this thread off the render thread's cores.
    while (session.run_script(true)) {
      session.update(glm::ivec2(options.width, options.height));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return session.status();
  } catch (const Error& e) {
    std::fprintf(stderr, "pss view: error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
}

}  // namespace pss::app::view
