// `pss view --headless` (issue 29: the viewer on a GPU server, which has no display): the
// session of the window run by its script alone, in every build and on every machine. Its
// screenshots are `pss render`'s images at the same camera, byte for byte; each view shows a
// reduced frame first, then the full one, timed; what it cannot do it refuses in one line.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli.hpp"
#include "support/shapes.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

class ViewerHeadless : public test::CliTest {
 protected:
  void SetUp() override {
    test::CliTest::SetUp();
    test::SampleOptions o;
    o.count = 3000;
    std::ofstream xyz(path("sphere.xyz"));
    xyz.precision(9);
    for (const vec3& p : test::sample(test::Sphere{}, o).positions) xyz << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  test::CliResult view(const std::string& args, const std::string& steps) {
    return test::run_pss("view " + path("sphere.xyz") + " --headless " + args + " --script " + write("steps.txt", steps) +
                         " --screenshot-dir " + dir_.string());
  }
};

TEST_F(ViewerHeadless, ScreenshotsAreTheRenderedImagesAtTheSameCamera) {
  const test::CliResult r = view("--size 200x150", "view 40 -25\nscreenshot a\nset reflections on\nzoom 1.7\nscreenshot b\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string render = "render " + path("sphere.xyz") + " --size 200x150";
  ASSERT_EQ(test::run_pss(render + " --view 40,-25 -o " + path("ra.png") + " --hits " + path("ra.ply")).exit_code, 0);
  EXPECT_EQ(read(path("a.png")), read(path("ra.png")));
  EXPECT_EQ(read(path("a.ply")), read(path("ra.ply")));
  ASSERT_EQ(test::run_pss(render + " --camera " + path("b.json") + " --reflections -o " + path("rb.png")).exit_code, 0);
  EXPECT_EQ(read(path("b.png")), read(path("rb.png")));
  EXPECT_NE(read(path("a.png")), read(path("b.png")));
  EXPECT_EQ(nlohmann::json::parse(read(path("b.json")))["width"], 200);
}

// Progressive refinement: before any frame has been timed a new view comes at a quarter of the
// size each way (render_thread.hpp), and each view's full frame follows; one timing line a view
// (a screenshot's second render of its view, with the hits, is not timed).
TEST_F(ViewerHeadless, EachViewComesReducedFirstThenFullAndIsTimed) {
  const test::CliResult r = view("--size 256x192", "wait\nview 90 0\nscreenshot s\nview 180 30\nwait\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::regex timing(R"(view timing: first frame at 1/(\d+) in [0-9.]+ s \(its render [0-9.]+ s\), full size in [0-9.]+ s)");
  std::vector<int> reductions;
  for (std::sregex_iterator m(r.out.begin(), r.out.end(), timing), end; m != end; ++m) reductions.push_back(std::stoi((*m)[1]));
  ASSERT_EQ(reductions.size(), 3u) << r.out;
  EXPECT_EQ(reductions[0], 4);
}

// A volume's fields stay on the device between frames (scene.cpp): a new iso-value or the
// Figure 2 view must still reach the screenshots, which are `pss volume`'s images.
TEST_F(ViewerHeadless, AVolumesChangesReachItsFrames) {
  write("ball.raw", test::uint8_raw_bytes(test::sphere_distance(vec3(15.0f, 16.0f, 14.0f), 8.0f), ivec3(32)));
  const std::string volume = path("ball.raw") + " --dims 32x32x32 --type uint8";
  const test::CliResult r = test::run_pss(
      "view " + volume + " --headless --iso 100 --size 160x120 --script " +
      write("steps.txt", "view 30 20\nscreenshot a\nset debug on\nscreenshot b\nset iso 90\nscreenshot c\n"
                         "set debug off\nscreenshot d\n") +
      " --screenshot-dir " + dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto volume_image = [&](const std::string& flags, const std::string& name) {
    EXPECT_EQ(test::run_pss("volume " + volume + " --size 160x120 --camera " + path("a.json") + " " + flags + " -o " +
                            path(name)).exit_code, 0);
    return read(path(name));
  };
  EXPECT_EQ(read(path("a.png")), volume_image("--iso 100", "ra.png"));
  EXPECT_EQ(read(path("b.png")), volume_image("--iso 100 --debug-projection", "rb.png"));
  EXPECT_EQ(read(path("c.png")), volume_image("--iso 90 --debug-projection", "rc.png"));
  EXPECT_EQ(read(path("d.png")), volume_image("--iso 90", "rd.png"));
  EXPECT_NE(read(path("a.png")), read(path("b.png")));
  EXPECT_NE(read(path("b.png")), read(path("c.png")));
}

// `set borders` (points/borders.hpp): a mesh's vertices open clipped (auto), and each choice
// reaches the screenshots, which are `pss render --borders`'s images; a value that is no mode
// is refused on its line.
TEST_F(ViewerHeadless, TheBordersChoiceReachesItsFrames) {
  test::SampleOptions o;
  o.count = 2000;
  const PointCloud square = test::sample_plane(1.0f, o);
  std::ofstream off(path("square.off"));
  off.precision(9);
  off << "OFF\n" << square.size() << " 1 0\n";
  for (const vec3& p : square.positions) off << p.x << ' ' << p.y << ' ' << p.z << '\n';
  off << "3 0 1 2\n";
  off.close();
  const test::CliResult r = test::run_pss(
      "view " + path("square.off") + " --headless --size 96x96 --script " +
      write("steps.txt", "view 20 50\nscreenshot a\nset borders extend\nscreenshot b\nset borders auto\nscreenshot c\n"
                         "set borders extend\nset borders clip\nscreenshot d\nset borders trim\n") +
      " --screenshot-dir " + dir_.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("steps.txt:10: expected auto or clip or extend"), std::string::npos) << r.err;
  const auto rendered = [&](const std::string& flags, const std::string& name) {
    EXPECT_EQ(test::run_pss("render " + path("square.off") + " --size 96x96 --camera " + path("a.json") + flags + " -o " +
                            path(name)).exit_code, 0);
    return read(path(name));
  };
  EXPECT_EQ(read(path("a.png")), rendered(" --borders clip", "ra.png"));
  EXPECT_EQ(read(path("b.png")), rendered(" --borders extend", "rb.png"));
  EXPECT_EQ(read(path("c.png")), read(path("a.png")));
  EXPECT_EQ(read(path("d.png")), read(path("a.png")));
  EXPECT_NE(read(path("a.png")), read(path("b.png")));
}

TEST_F(ViewerHeadless, RefusesWhatItCannotDo) {
  test::CliResult r = test::run_pss("view " + path("sphere.xyz") + " --headless");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--script"), std::string::npos) << r.err;
  r = view("", "view 10 10\nwindow w\n");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("steps.txt:2: no window"), std::string::npos) << r.err;
  EXPECT_EQ(read(path("w.png")), "");
  // A refused value leaves the last frame on screen, which a window only showed: no hits to write.
  r = view("", "wait\nset iterations 0\nscreenshot s\n");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("steps.txt:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("iterations must be at least 1"), std::string::npos) << r.err;
  EXPECT_EQ(read(path("s.png")), "");
  r = test::run_pss("view " + path("none.xyz") + " --headless --script " + write("shot.txt", "screenshot s\n") +
                    " --screenshot-dir " + dir_.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none.xyz"), std::string::npos) << r.err;
  EXPECT_EQ(read(path("s.png")), "");
}

// Without --headless a build without the window says so; one with it says "in a window".
TEST_F(ViewerHeadless, AWindowlessBuildSaysSo) {
  const test::CliResult help = test::run_pss("view --help");
  ASSERT_EQ(help.exit_code, 0);
  if (PSS_HAVE_VIEWER) {
    EXPECT_NE(help.out.find("in a window"), std::string::npos);
  } else {
    EXPECT_NE(help.out.find("--headless only"), std::string::npos);
    const test::CliResult r = test::run_pss("view " + path("sphere.xyz"));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("use --headless"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace pss
