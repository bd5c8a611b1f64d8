// `pss view` (issue 11) run headless on Xvfb with Mesa: its full-size screenshots are the
// batch commands' images at the same camera, byte for byte; the camera file round-trips; a
// value out of range or an unreadable file shows a message and does not end the viewer. The
// reduced frames it shows while the camera moves are the full frame at a lower resolution.
// The window tests skip in builds without the viewer or on machines without Xvfb.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "pss/points/render_cloud.hpp"
#include "pss/render/image.hpp"
#include "support/cli.hpp"
#include "support/shapes.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

// A virtual X display (Xvfb with Mesa) for the window tests. Xvfb picks a free display and
// writes its number once it accepts clients (-displayfd): xvfb-run instead waits for a
// signal that can come before it waits, and then hangs.
class VirtualDisplay {
 public:
  VirtualDisplay() {
    dir_ = fs::temp_directory_path() / ("pss-xvfb-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const std::string start = "Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp 3>" + (dir_ / "display").string() +
                              " 2>" + (dir_ / "log").string() + " & echo $! >" + (dir_ / "pid").string();
    if (std::system("command -v Xvfb >/dev/null 2>&1") != 0 || std::system(start.c_str()) != 0) return;
    for (int tries = 0; tries < 200 && number_.empty(); ++tries) {  // up to 20 s
      std::ifstream in(dir_ / "display");
      std::string n;
      if (std::getline(in, n) && !n.empty()) number_ = n;
      else ::usleep(100000);
    }
  }
  ~VirtualDisplay() {
    std::ifstream pid(dir_ / "pid");
    std::string p;
    if (std::getline(pid, p) && !p.empty()) std::system(("kill " + p + " 2>/dev/null").c_str());
    fs::remove_all(dir_);
  }
  const std::string& number() const { return number_; }  // empty: none

 private:
  fs::path dir_;
  std::string number_;
};

class Viewer : public test::CliTest {
 protected:
  static void SetUpTestSuite() { display_ = new VirtualDisplay; }
  static void TearDownTestSuite() {
    delete display_;
    display_ = nullptr;
  }
  void SetUp() override {
    test::CliTest::SetUp();
    if (!PSS_HAVE_VIEWER) GTEST_SKIP() << "this build has no viewer (GLFW or Dear ImGui missing)";
    if (display_->number().empty()) GTEST_SKIP() << "no virtual display: Xvfb is not installed or did not start";
    test::SampleOptions o;
    o.count = 3000;
    cloud_ = test::sample(test::Sphere{}, o);
    std::ofstream xyz(path("sphere.xyz"));
    xyz.precision(9);  // read back, the same floats: the same box
    for (const vec3& p : cloud_.positions) xyz << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  PointCloud cloud_;
  static VirtualDisplay* display_;

  // `pss view ARGS --script (steps) --screenshot-dir (the test's folder)` on the virtual
  // display, stopped after two minutes if it hangs. Mesa's and X11's own allocations outlive
  // the process, so leak reports are off for it alone (the sanitized suite exports
  // ASAN_OPTIONS).
  test::CliResult view(const std::string& args, const std::string& steps) {
    write("steps.txt", steps);
    const std::string asan = std::getenv("ASAN_OPTIONS") ? std::getenv("ASAN_OPTIONS") : "";
    const std::string command = "env DISPLAY=:" + display_->number() + " ASAN_OPTIONS=" + asan +
                                (asan.empty() ? "" : ":") + "detect_leaks=0 timeout 120 " + PSS_CLI + " view " + args +
                                " --script " + path("steps.txt") + " --screenshot-dir " + dir_.string();
    return run_shell(command);
  }
  test::CliResult run_shell(const std::string& command) {
    const std::string out = path("out.txt"), err = path("err.txt");
    const int status = std::system((command + " >" + out + " 2>" + err).c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read(out), read(err)};
  }
};

VirtualDisplay* Viewer::display_ = nullptr;

TEST_F(Viewer, ScreenshotsAreTheRenderedImagesAtTheSameCamera) {
  const test::CliResult r = view(path("sphere.xyz") + " --size 200x150",
                                 "view 40 -25\nscreenshot a\n"
                                 "set reflections on\nset iterations 3\nzoom 1.7\npan 0.05 0.02\nscreenshot b\n"
                                 "camera " + path("a.json") + "\nscreenshot c\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string render = "render " + path("sphere.xyz") + " --size 200x150";
  ASSERT_EQ(test::run_pss(render + " --view 40,-25 -o " + path("ra.png") + " --hits " + path("ra.ply")).exit_code, 0);
  EXPECT_EQ(read(path("a.png")), read(path("ra.png")));  // the viewer's orbit is --view's
  EXPECT_EQ(read(path("a.ply")), read(path("ra.ply")));  // and its hits, --hits
  ASSERT_EQ(test::run_pss(render + " --camera " + path("b.json") + " --reflections --iterations 3 -o " + path("rb.png"))
                .exit_code, 0);
  EXPECT_EQ(read(path("b.png")), read(path("rb.png")));
  EXPECT_NE(read(path("a.png")), read(path("b.png")));
  // The camera file round-trips: loaded back, the view of a, with b's settings.
  ASSERT_EQ(test::run_pss(render + " --camera " + path("a.json") + " --reflections --iterations 3 -o " + path("rc.png"))
                .exit_code, 0);
  EXPECT_EQ(read(path("c.png")), read(path("rc.png")));
  const auto camera_of = [&](const char* f) { return nlohmann::json::parse(read(path(f)))["camera"]; };
  EXPECT_EQ(camera_of("a.json"), camera_of("c.json"));
  // Zoom 1.7 brings the eye 1.7 times closer to the centre of the framed box, and the pan
  // moves it by (0.05, 0.02) of the framing distance along right and up.
  const auto vec = [](const nlohmann::json& j) { return vec3(j[0].get<float>(), j[1].get<float>(), j[2].get<float>()); };
  const nlohmann::json a = camera_of("a.json"), b = camera_of("b.json");
  const vec3 centre = cloud_.bounds().center();
  const float distance = glm::length(vec(a["eye"]) - centre);
  const vec3 expected = centre + (vec(a["eye"]) - centre) / 1.7f +
                        distance * (0.05f * vec(a["right"]) + 0.02f * vec(a["up"]));
  EXPECT_LT(glm::length(vec(b["eye"]) - expected), 1e-5f * distance);
  EXPECT_EQ(b["forward"], a["forward"]);
}

// The panel's support: adaptive by default, as pss render's; global when set, as
// --support global's. A sphere with its half x < 0 sampled 64 times sparser tells them apart.
TEST_F(Viewer, SupportIsTheRenderedOne) {
  test::SampleOptions o;
  o.count = 20000;
  o.step = 64;
  {
    std::ofstream xyz(path("step.xyz"));
    xyz.precision(9);
    for (const vec3& p : test::sample(test::Sphere{}, o).positions) xyz << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  const test::CliResult r =
      view(path("step.xyz") + " --size 96x96", "view 180 0\nscreenshot a\nset support global\nscreenshot g\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string render = "render " + path("step.xyz") + " --size 96x96 --view 180,0 -o ";
  ASSERT_EQ(test::run_pss(render + path("ra.png")).exit_code, 0);
  ASSERT_EQ(test::run_pss(render + path("rg.png") + " --support global").exit_code, 0);
  EXPECT_EQ(read(path("a.png")), read(path("ra.png")));
  EXPECT_EQ(read(path("g.png")), read(path("rg.png")));
  EXPECT_NE(read(path("a.png")), read(path("g.png")));
}

// The panel's surface: RIMLS by default, as pss render's; MLS and APSS when set, as
// --surface's (the cloud prepared again without normals and with them, then switched back).
TEST_F(Viewer, SurfaceIsTheRenderedOne) {
  test::SampleOptions o;
  o.count = 6000;
  {
    std::ofstream xyz(path("sphere.xyz"));
    xyz.precision(9);
    for (const vec3& p : test::sample(test::Sphere{}, o).positions) xyz << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  const test::CliResult r = view(path("sphere.xyz") + " --size 96x96",
                                 "view 30 20\nscreenshot r\nset surface mls\nscreenshot m\nset surface apss\n"
                                 "screenshot a\nset surface rimls\nscreenshot r2\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string render = "render " + path("sphere.xyz") + " --size 96x96 --view 30,20 -o ";
  for (const char* surface : {"mls", "rimls", "apss"})
    ASSERT_EQ(test::run_pss(render + path(std::string("r_") + surface + ".png") + " --surface " + surface).exit_code, 0);
  EXPECT_EQ(read(path("m.png")), read(path("r_mls.png")));
  EXPECT_EQ(read(path("r.png")), read(path("r_rimls.png")));
  EXPECT_EQ(read(path("a.png")), read(path("r_apss.png")));
  EXPECT_EQ(read(path("r2.png")), read(path("r_rimls.png")));
  EXPECT_NE(read(path("m.png")), read(path("r.png")));
  EXPECT_NE(read(path("m.png")), read(path("a.png")));
}

TEST_F(Viewer, VolumeScreenshotsAreThoseOfPssVolume) {
  write("ball.raw", test::uint8_raw_bytes(test::sphere_distance(vec3(15.0f, 16.0f, 14.0f), 8.0f), ivec3(32)));
  const std::string volume = path("ball.raw") + " --dims 32x32x32 --type uint8";
  const test::CliResult r = view(volume + " --iso 100 --size 160x120", "view 30 20\nset iso 90\nscreenshot a\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(test::run_pss("volume " + volume + " --iso 90 --size 160x120 --camera " + path("a.json") + " -o " +
                          path("ra.png")).exit_code, 0);
  EXPECT_EQ(read(path("a.png")), read(path("ra.png")));
  // An iso-value outside the data: its message, and the last surface stays on screen.
  const test::CliResult bad = view(volume + " --iso 100 --size 160x120", "screenshot b\nset iso 1e9\nscreenshot c\n");
  EXPECT_EQ(bad.exit_code, 0) << bad.err;
  EXPECT_NE(bad.err.find("lies outside the volume's values"), std::string::npos) << bad.err;
  EXPECT_EQ(read(path("b.png")), read(path("c.png")));
}

TEST_F(Viewer, AValueOutOfRangeShowsItsMessageAndTheViewerGoesOn) {
  const test::CliResult r = view(path("sphere.xyz") + " --size 120x90",
                                 "screenshot a\nset iterations 0\nscreenshot b\nset iterations 2\nview 90 0\nscreenshot c\n");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("iterations must be at least 1"), std::string::npos) << r.err;
  EXPECT_EQ(read(path("a.png")), read(path("b.png")));  // the last image stays
  EXPECT_TRUE(fs::exists(path("c.png")));
  EXPECT_NE(read(path("a.png")), read(path("c.png")));  // and later views still render
}

TEST_F(Viewer, AnUnreadableFileOpensTheWindowWithItsMessage) {
  const test::CliResult r = view(path("missing.ply") + " --size 320x200", "window w\n");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("missing.ply"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(path("w.png")));
  // A script that cannot be run is refused before any window opens (here there is no
  // display at all), naming its line.
  write("steps.txt", "view 10 10\nspin 3\n");
  const test::CliResult s = run_shell("env -u DISPLAY " + std::string(PSS_CLI) + " view " + path("sphere.xyz") +
                                      " --script " + path("steps.txt"));
  EXPECT_NE(s.exit_code, 0);
  EXPECT_EQ(test::line_count(s.err), 1) << s.err;
  EXPECT_NE(s.err.find("steps.txt:2"), std::string::npos) << s.err;
}

// What the viewer shows while the camera moves (Camera::reduced): every pixel of the
// quarter-size frame is the full frame's 4×4 block around the same point of the image, up to
// the shading's change across the block; hit and miss agree but at the silhouette.
TEST(ReducedFrame, IsTheFullFrameAtALowerResolution) {
  test::SampleOptions o;
  o.count = 3000;
  const PointCloud cloud = test::sample(test::Sphere{}, o);
  Stats stats;
  const PreparedCloud prepared(cloud, RayPssParams::from_h(test::suggested_h(cloud)), Backend::cpu, stats);
  CameraSettings s;
  s.width = 128;
  s.height = 96;
  const Camera full = Camera::framing(cloud.bounds(), s);
  const Camera quarter = full.reduced(4);
  ASSERT_EQ(quarter.width, 32);
  ASSERT_EQ(quarter.height, 24);
  EXPECT_EQ(full.reduced(1).width, 128);
  EXPECT_EQ(Camera(full).reduced(1000).width, 1);
  const RenderedFrame big = render_cloud(prepared, full, TraceSettings{}, Backend::cpu, stats);
  const RenderedFrame small = render_cloud(prepared, quarter, TraceSettings{}, Backend::cpu, stats);
  int agree = 0, interior = 0;
  double difference = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      int hits = 0;
      vec3 mean(0.0f);
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          hits += big.hits[std::size_t((4 * y + j) * 128 + 4 * x + i)].found();
          mean += big.image.at(4 * x + i, 4 * y + j) / 16.0f;
        }
      const bool hit = small.hits[std::size_t(y * 32 + x)].found();
      agree += hit == (hits >= 8);
      if (hits == 16 && hit) {
        ++interior;
        difference += glm::length(small.image.at(x, y) - mean);
      }
    }
  EXPECT_GE(agree, 32 * 24 - 16);  // the silhouette's 4-pixel band decides a few
  ASSERT_GT(interior, 100);
  EXPECT_LT(difference / interior, 0.02) << agree;  // linear RGB in [0, 1]
}

}  // namespace
}  // namespace pss
