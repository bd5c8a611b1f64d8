// The camera file (render/camera_file.hpp): a camera pss wrote loads bit for bit, one
// written by hand is made orthonormal, and what is not a camera is refused naming the
// file; `pss render` and `pss volume` accept their own --stats file as --camera and render
// the same image.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "pss/render/camera_file.hpp"
#include "support/cli.hpp"
#include "support/shapes.hpp"
#include "support/volumes.hpp"

namespace pss {
namespace {

namespace fs = std::filesystem;

using CameraFile = test::CliTest;

// The eye is written as a world position: a camera saved about one cloud's origin (a
// georeferenced tile, points/cloud.hpp) places the same eye about another's.
TEST_F(CameraFile, TheEyeIsAWorldPositionAcrossOrigins) {
  Camera c = Camera::framing(Aabb{vec3(-1.0f), vec3(1.0f)}, CameraSettings{});
  c.eye = vec3(1.5f, -2.25f, 3.0f);
  const glm::dvec3 a(500000, 4000000, 0), b(500016, 4000032, 16);
  const nlohmann::json json = camera_to_json(c, a);
  EXPECT_EQ(json["eye"], nlohmann::json({500001.5, 3999997.75, 3.0}));
  const std::string file = write("camera.json", json.dump());
  EXPECT_EQ(read_camera_file(file, 4, 4, b).eye, vec3(-14.5f, -34.25f, -13.0f));
  EXPECT_EQ(read_camera_file(file, 4, 4, a).eye, c.eye);
}

TEST_F(CameraFile, ACameraPssWroteLoadsBitForBit) {
  for (const auto& [az, el] : {std::pair{0.0f, 0.0f}, {30.0f, 20.0f}, {-123.4f, 89.0f}, {200.0f, -90.0f}}) {
    CameraSettings s;
    s.azimuth_deg = az;
    s.elevation_deg = el;
    s.fov_deg = 27.5f;
    const Camera c = Camera::framing(Aabb{vec3(-1.0f, 2.0f, 3.0f), vec3(4.0f, 5.5f, 6.0f)}, s);
    const std::string file =
        write("camera.json", nlohmann::json{{"camera", camera_to_json(c, glm::dvec3(0.0))}}.dump());
    const Camera back = read_camera_file(file, 7, 9, glm::dvec3(0.0));
    EXPECT_EQ(back.eye, c.eye) << az << ", " << el;
    EXPECT_EQ(back.forward, c.forward);
    EXPECT_EQ(back.right, c.right);
    EXPECT_EQ(back.up, c.up);
    EXPECT_EQ(back.tan_half_fov, c.tan_half_fov);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 9);
  }
}

TEST_F(CameraFile, AHandWrittenCameraIsMadeOrthonormal) {
  // Looking along −x from (10, 0, 0), up tilted toward the view and twice too long.
  const std::string file = write("hand.json", R"({"eye": [10, 0, 0], "forward": [-3, 0, 0], "up": [1, 2, 0],
                                                  "tan_half_fov": 0.5})");
  const Camera c = read_camera_file(file, 4, 4, glm::dvec3(0.0));
  EXPECT_EQ(c.eye, vec3(10, 0, 0));
  EXPECT_NEAR(glm::length(c.forward - vec3(-1, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(c.up - vec3(0, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(c.right - vec3(0, 0, -1)), 0.0f, 1e-6f);  // forward × up
  // The centre pixel's ray of a 1×1 image is the forward direction.
  Camera one = c;
  one.width = one.height = 1;
  EXPECT_NEAR(glm::length(one.primary_ray(0, 0).dir - c.forward), 0.0f, 1e-6f);
}

TEST_F(CameraFile, WhatIsNotACameraIsRefusedNamingTheFile) {
  const std::string good = R"("eye": [0, 0, 5], "forward": [0, 0, -1], "up": [0, 1, 0])";
  const std::string cases[] = {
      "",
      "not json",
      "[1, 2, 3]",
      R"({"camera": 3})",
      "{" + good + "}",                                          // no tan_half_fov
      "{" + good + R"(, "tan_half_fov": "wide"})",
      "{" + good + R"(, "tan_half_fov": 0})",
      "{" + good + R"(, "tan_half_fov": 1e9})",
      R"({"eye": [0, 0], "forward": [0, 0, -1], "up": [0, 1, 0], "tan_half_fov": 0.3})",
      R"({"eye": [0, 0, 1e300], "forward": [0, 0, -1], "up": [0, 1, 0], "tan_half_fov": 0.3})",
      R"({"eye": [0, 0, 5], "forward": [0, 0, 0], "up": [0, 1, 0], "tan_half_fov": 0.3})",
      R"({"eye": [0, 0, 5], "forward": [0, 0, -1], "up": [0, 0, 2], "tan_half_fov": 0.3})",
      R"({"eye": [0, 0, 5], "up": [0, 1, 0], "tan_half_fov": 0.3})",
      // "right" mirrored, or along up: not forward × up (it was ignored without a word)
      "{" + good + R"(, "right": [-1, 0, 0], "tan_half_fov": 0.3})",
      "{" + good + R"(, "right": [0, 1, 0], "tan_half_fov": 0.3})",
      "{",
  };
  for (const std::string& text : cases) {
    const std::string file = write("bad camera.json", text);
    const std::string message = test::error_of([&] { read_camera_file(file, 4, 4, glm::dvec3(0.0)); });
    EXPECT_NE(message.find("bad camera.json"), std::string::npos) << text << " → " << message;
  }
  EXPECT_NE(test::error_of([&] { read_camera_file(write("m.json", "{" + good + R"(, "right": [-1, 0, 0], "tan_half_fov": 0.3})"),
                                                   4, 4, glm::dvec3(0.0)); })
                .find("\"right\" must be forward x up"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] { read_camera_file(write("s.json", "{"), 4, 4, glm::dvec3(0.0)); }).find("is not JSON (expected a camera): a syntax error at byte 2"),
            std::string::npos);
  // A "right" of any length along forward × up is that, as a hand-written file may give it.
  const Camera scaled = read_camera_file(write("r.json", "{" + good + R"(, "right": [3, 0, 0], "tan_half_fov": 0.3})"), 4, 4,
                                         glm::dvec3(0.0));
  EXPECT_NEAR(glm::length(scaled.right - vec3(1, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NE(test::error_of([&] { read_camera_file(path("missing.json"), 4, 4, glm::dvec3(0.0)); }).find("missing.json"),
            std::string::npos);
  std::ofstream(path("huge.json")) << std::string(2 << 20, ' ');
  EXPECT_NE(test::error_of([&] { read_camera_file(path("huge.json"), 4, 4, glm::dvec3(0.0)); }).find("too large"),
            std::string::npos);
}

TEST_F(CameraFile, RenderAcceptsItsOwnStatsAsTheCamera) {
  test::SampleOptions o;
  o.count = 2000;
  std::ofstream xyz(path("sphere.xyz"));
  for (const vec3& p : test::sample(test::Sphere{}, o).positions) xyz << p.x << ' ' << p.y << ' ' << p.z << '\n';
  xyz.close();
  const std::string common = "render " + path("sphere.xyz") + " --size 40x30";
  ASSERT_EQ(test::run_pss(common + " --view 40,-25 --fov 50 -o " + path("a.png") + " --stats " + path("a.json")).exit_code, 0);
  const test::CliResult r = test::run_pss(common + " --camera " + path("a.json") + " -o " + path("b.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read(path("a.png")), read(path("b.png")));
  // And not merely the default view: without the camera the image differs.
  ASSERT_EQ(test::run_pss(common + " -o " + path("c.png")).exit_code, 0);
  EXPECT_NE(read(path("a.png")), read(path("c.png")));
}

TEST_F(CameraFile, VolumeAcceptsItsOwnStatsAsTheCamera) {
  write("ball.raw", test::uint8_raw_bytes(test::sphere_distance(vec3(15.0f, 16.0f, 14.0f), 8.0f), ivec3(32)));
  const std::string common = "volume " + path("ball.raw") + " --dims 32x32x32 --type uint8 --iso 100 --size 40x30";
  ASSERT_EQ(test::run_pss(common + " --view 30,20 -o " + path("a.png") + " --stats " + path("a.json")).exit_code, 0);
  const test::CliResult r = test::run_pss(common + " --camera " + path("a.json") + " -o " + path("b.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read(path("a.png")), read(path("b.png")));
}

TEST_F(CameraFile, BadCameraFlagsFailCleanly) {
  std::ofstream(path("one.xyz")) << "1 2 3\n0 0 0\n1 0 0\n";
  write("camera.json", R"({"eye": [0, 0, 5], "forward": [0, 0, -1], "up": [0, 0, 1], "tan_half_fov": 0.3})");
  const std::string render = "render " + path("one.xyz") + " -o " + path("out.png") + " --size 8x8 --h 1";
  expect_clean_failure(render + " --camera " + path("camera.json"), "camera.json", path("out.png"));
  expect_clean_failure(render + " --camera " + path("missing.json"), "missing.json", path("out.png"));
  expect_clean_failure(render + " --camera " + path("camera.json") + " --view 10,10", "--view", path("out.png"));
  expect_clean_failure(render + " --camera " + path("camera.json") + " --stats " + path("camera.json"), "camera.json",
                       path("out.png"));
  expect_clean_failure(render + " --camera " + path("camera.json") + " --zoom 2", "--zoom", path("out.png"));
  expect_clean_failure(render + " --look-at 1,2", "--look-at", path("out.png"));
  expect_clean_failure(render + " --look-at 1,2,nan", "--look-at", path("out.png"));
  // Finite but beyond the camera's reach: the message says how far it may be.
  const test::CliResult far = test::run_pss(render + " --look-at 1e30,0,0");
  EXPECT_NE(far.err.find("less than 1e30 from zero"), std::string::npos) << far.err;
  expect_clean_failure(render + " --up 0,0,0", "--up", path("out.png"));
  expect_clean_failure(render + " --distance -1", "--distance", path("out.png"));
  expect_clean_failure(render + " --zoom 0", "--zoom", path("out.png"));
  expect_clean_failure(render + " --roll inf", "--roll", path("out.png"));
  // Straight down about another up is a view like any other (it was refused).
  const test::CliResult top = test::run_pss("render " PSS_SOURCE_DIR "/data/bun_zipper.ply -o " + path("out.png") +
                                            " --size 16x16 --up 0,0,1 --view 0,90");
  EXPECT_EQ(top.exit_code, 0) << top.err;
  EXPECT_TRUE(std::filesystem::exists(path("out.png")));
}

}  // namespace
}  // namespace pss
