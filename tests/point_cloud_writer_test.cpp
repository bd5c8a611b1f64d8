// PointCloudWriter (issue 28): a cloud written part by part is the file its whole-cloud
// writer makes, byte for byte, and a wrong part or a short count leaves no file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "pss/core/error.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "pss/io/point_cloud_writer.hpp"
#include "support/cli.hpp"

namespace {

using pss::PlyIntProperty;
using pss::PointCloud;
using pss::PointCloudWriter;
using pss::ScalarType;
using pss::vec3;
using WriterTest = pss::test::CliTest;

const glm::dvec3 kGeoreferenced(596700.0, 4000000.0, 120.25);

// n points with what is asked for, values that vary in every byte of their records.
PointCloud sample(std::size_t n, glm::dvec3 origin, bool normals, bool extras) {
  PointCloud cloud;
  cloud.origin = origin;
  for (std::size_t i = 0; i < n; ++i) {
    const float t = 0.001f * float(i);
    cloud.positions.push_back(vec3(std::sin(t) * 30.0f, t, i == 2 ? -0.0f : std::cos(t) * 1e3f));
    if (normals) cloud.normals.push_back(vec3(std::cos(t), 0.0f, std::sin(t)));
    if (extras) cloud.colors.push_back(pss::Rgb8(i % 256, (7 * i) % 256, 255 - i % 256));
  }
  if (extras) {
    // 'status' is also an extra property below: written as input_status, past the taken name.
    cloud.scalars = {{"status", ScalarType::uint8, {}},
                     {"input_status", ScalarType::int16, {}},
                     {"intensity", ScalarType::float32, {}},
                     {"gps_time", ScalarType::float64, {}}};
    for (std::size_t i = 0; i < n; ++i) {
      cloud.scalars[0].values.push_back(double(i % 200));
      cloud.scalars[1].values.push_back(double(int(i % 60000) - 30000));
      cloud.scalars[2].values.push_back(double(float(0.25 * double(i))));
      cloud.scalars[3].values.push_back(1e9 + 1e-3 * double(i));
    }
  }
  return cloud;
}

// Points [begin, end) of `cloud`, about its origin.
PointCloud part_of(const PointCloud& cloud, std::size_t begin, std::size_t end) {
  const auto slice = [&](const auto& values) {
    using Values = std::decay_t<decltype(values)>;
    return values.empty() ? Values{} : Values(values.begin() + begin, values.begin() + end);
  };
  PointCloud part;
  part.origin = cloud.origin;
  part.positions = slice(cloud.positions);
  part.normals = slice(cloud.normals);
  part.colors = slice(cloud.colors);
  for (const pss::ScalarProperty& s : cloud.scalars) part.scalars.push_back({s.name, s.type, slice(s.values)});
  return part;
}

struct Extra {
  std::vector<std::int32_t> status, px;
  std::vector<PlyIntProperty> of(std::size_t begin, std::size_t end) const {
    return {{"status", std::span(status).subspan(begin, end - begin)}, {"px", std::span(px).subspan(begin, end - begin)}};
  }
};

Extra extra_for(std::size_t n) {
  Extra extra;
  for (std::size_t i = 0; i < n; ++i) {
    extra.status.push_back(int(i % 5) - 2);
    extra.px.push_back(int(i) * 1031);
  }
  return extra;
}

// `cloud` written in three uneven parts, the middle one past a PLY record chunk (65536) and
// an XYZ write (1 MiB), with its extra properties when `extra` is given.
void write_in_parts(const std::string& path, const PointCloud& cloud, const Extra* extra) {
  const std::size_t n = cloud.size();
  const std::size_t cuts[] = {0, n / 10, n - 3, n};
  const auto extra_of = [&](std::size_t begin, std::size_t end) {
    return extra ? extra->of(begin, end) : std::vector<PlyIntProperty>{};
  };
  PointCloudWriter writer(path, pss::layout_of(cloud, extra_of(0, n)));
  for (int k = 0; k < 3; ++k) writer.append(part_of(cloud, cuts[k], cuts[k + 1]), extra_of(cuts[k], cuts[k + 1]));
  writer.commit();
}

TEST_F(WriterTest, PartsMakeTheWholePlyWithOriginNormalsColoursScalarsAndExtras) {
  const PointCloud cloud = sample(80000, kGeoreferenced, true, true);
  const Extra extra = extra_for(cloud.size());
  pss::write_point_cloud(path("whole.ply"), cloud, extra.of(0, cloud.size()));
  write_in_parts(path("parts.ply"), cloud, &extra);
  const std::string whole = read(path("whole.ply"));
  EXPECT_NE(whole.find("property double x\n"), std::string::npos);
  EXPECT_NE(whole.find("property uchar input_input_status\nproperty short input_status\n"), std::string::npos);
  EXPECT_EQ(read(path("parts.ply")), whole);
}

TEST_F(WriterTest, PartsMakeTheWholePlyOfFloats) {
  for (const bool normals : {false, true}) {
    const PointCloud cloud = sample(70001, glm::dvec3(0.0), normals, false);
    pss::write_point_cloud(path("whole.ply"), cloud);
    write_in_parts(path("parts.PLY"), cloud, nullptr);
    const std::string whole = read(path("whole.ply"));
    EXPECT_NE(whole.find("property float x\n"), std::string::npos);
    EXPECT_EQ(read(path("parts.PLY")), whole) << normals;
  }
}

TEST_F(WriterTest, PartsMakeTheWholeXyz) {
  for (const glm::dvec3 origin : {glm::dvec3(0.0), kGeoreferenced})
    for (const bool normals : {false, true}) {
      const PointCloud cloud = sample(50000, origin, normals, false);
      pss::write_point_cloud(path("whole.xyz"), cloud);
      write_in_parts(path("parts.XYZ"), cloud, nullptr);
      EXPECT_EQ(read(path("parts.XYZ")), read(path("whole.xyz"))) << normals << " " << origin.x;
    }
}

TEST_F(WriterTest, DestinationAppearsAtCommit) {
  const PointCloud cloud = sample(10, glm::dvec3(0.0), true, false);
  PointCloudWriter writer(path("c.ply"), pss::layout_of(cloud));
  writer.append(part_of(cloud, 0, 4));
  EXPECT_FALSE(std::filesystem::exists(path("c.ply")));
  writer.append(part_of(cloud, 4, 10));
  EXPECT_FALSE(std::filesystem::exists(path("c.ply")));
  writer.commit();
  EXPECT_TRUE(std::filesystem::exists(path("c.ply")));
}

TEST_F(WriterTest, TooFewPointsThrowAtCommitAndLeaveNoFile) {
  const PointCloud cloud = sample(10, kGeoreferenced, false, false);
  {
    PointCloudWriter writer(path("c.xyz"), pss::layout_of(cloud));
    writer.append(part_of(cloud, 0, 9));
    EXPECT_EQ(pss::test::error_of([&] { writer.commit(); }),
              path("c.xyz") + ": cannot write: 9 of the 10 points declared");
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir_));  // no temporary either
}

TEST_F(WriterTest, MorePointsThanDeclaredThrow) {
  const PointCloud cloud = sample(10, glm::dvec3(0.0), false, false);
  PointCloudWriter writer(path("c.ply"), pss::layout_of(part_of(cloud, 0, 6)));
  writer.append(part_of(cloud, 0, 4));
  EXPECT_EQ(pss::test::error_of([&] { writer.append(part_of(cloud, 4, 7)); }),
            path("c.ply") + ": cannot write: more than the 6 points declared");
  // The refused part wrote nothing: the count can still be met.
  writer.append(part_of(cloud, 4, 6));
  writer.commit();
  EXPECT_EQ(pss::read_point_cloud(path("c.ply")).positions, part_of(cloud, 0, 6).positions);
}

TEST_F(WriterTest, PartAboutAnotherOriginThrows) {
  const PointCloud cloud = sample(10, kGeoreferenced, false, false);
  {
    PointCloudWriter writer(path("c.ply"), pss::layout_of(cloud));
    PointCloud part = part_of(cloud, 0, 10);
    part.origin.z += 1.0;
    EXPECT_EQ(pss::test::error_of([&] { writer.append(part); }),
              path("c.ply") + ": cannot write: a part about (596700, 4e+06, 121.25), not the cloud's origin "
                              "(596700, 4e+06, 120.25)");
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

// A part is checked as write_ply checks a whole cloud, against the layout.
TEST_F(WriterTest, PartsUnlikeTheLayoutThrow) {
  const PointCloud cloud = sample(4, glm::dvec3(0.0), true, true);
  const Extra extra = extra_for(4);
  PointCloudWriter writer(path("c.ply"), pss::layout_of(cloud, extra.of(0, 4)));
  const auto refused = [&](const PointCloud& part, std::span<const PlyIntProperty> spans, const std::string& problem) {
    EXPECT_EQ(pss::test::error_of([&] { writer.append(part, spans); }), path("c.ply") + ": cannot write: " + problem);
  };
  PointCloud part = part_of(cloud, 0, 2);
  part.normals.pop_back();
  refused(part, extra.of(0, 2), "2 positions but 1 normals");
  part = part_of(cloud, 0, 2);
  part.scalars[0].values[1] = 256;
  refused(part, extra.of(0, 2), "value 256 of 'status' does not fit its type uchar");
  part.scalars.pop_back();
  refused(part, extra.of(0, 2), "a part with 3 scalars, not the cloud's 4");
  part = part_of(cloud, 0, 2);
  part.scalars[2].name = "reflectance";
  refused(part, extra.of(0, 2), "a part's scalar 'reflectance' where the cloud has 'intensity'");
  refused(part_of(cloud, 0, 2), extra.of(0, 1), "2 positions but 1 values of 'status'");
  refused(part_of(cloud, 0, 2), {}, "0 extra properties for the cloud's 2");
}

TEST_F(WriterTest, NamesAreCheckedBeforeTheFileIsMade) {
  PointCloud cloud = sample(4, glm::dvec3(0.0), false, true);
  cloud.scalars[2].name = "x";
  EXPECT_EQ(pss::test::error_of([&] { PointCloudWriter(path("c.ply"), pss::layout_of(cloud)); }),
            path("c.ply") + ": cannot write: two properties named 'x'");
  EXPECT_NE(pss::test::error_of([&] { PointCloudWriter(path("c.las"), pss::layout_of(cloud)); }), "");
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

}  // namespace
