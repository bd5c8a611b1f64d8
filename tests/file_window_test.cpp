// The readers of the large formats (PLY, XYZ, LAS) see a file through a window of its bytes
// (src/io/file_window.hpp, issue 28): whatever the window, they read the same cloud or
// refuse with the same message, and a read holds the cloud, not the file as well.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../src/io/file_window.hpp"
#include "pss/core/memory.hpp"
#include "pss/io/point_cloud_file.hpp"
#include "support/cli.hpp"
#include "support/file_bytes.hpp"

namespace pss {
namespace {

using io::FileWindow;

class FileWindowTest : public test::CliTest {
 protected:
  void TearDown() override {
    FileWindow::set_default_window(kDefault);
    test::CliTest::TearDown();
  }
  static inline const std::size_t kDefault = FileWindow::default_window();
  void expect_the_same_whatever_the_window(const std::string& name, const std::string& bytes);
};

using test::bytes_of;

TEST_F(FileWindowTest, AWindowOfAnySizeGivesTheFilesBytesInOrder) {
  std::string bytes;
  for (int i = 0; i < 1000; ++i) bytes += char(i * 7 % 251);
  const std::string file = write("b.bin", bytes);
  for (const std::size_t window : {1u, 2u, 7u, 64u, 4096u}) {
    SCOPED_TRACE(window);
    FileWindow w(file, window);
    EXPECT_EQ(w.size(), 1000u);
    std::string seen;
    for (std::size_t step = 1; w.fill(step); step = step % 13 + 1) {
      ASSERT_GE(w.view().size(), step);
      seen += w.view().substr(0, step);
      w.consume(step);
      if (seen.size() > 500 && seen.size() < 600) {  // a skip across the window
        ASSERT_TRUE(w.skip(100));
        seen += bytes.substr(seen.size(), 100);
      }
    }
    EXPECT_EQ(seen, bytes.substr(0, seen.size()));
    EXPECT_GT(seen.size(), 1000u - 13);
    EXPECT_EQ(w.offset(), seen.size());
    EXPECT_FALSE(w.skip(1000));
  }
}

// A count the file cannot hold never sizes the buffer; a file that shrinks while it is read
// ends where its bytes do.
TEST_F(FileWindowTest, FillingBeyondTheFileFailsAndAShrunkFileEndsEarly) {
  const std::string file = write("s.bin", std::string(100000, 'x'));
  FileWindow w(file, 16);
  EXPECT_FALSE(w.fill(std::size_t(1) << 40));
  ASSERT_TRUE(w.fill(10));
  w.consume(10);
  std::filesystem::resize_file(file, 50);
  EXPECT_FALSE(w.skip(90000));  // beyond what the C library read ahead before the cut
  EXPECT_THROW(FileWindow(dir_.string()), Error);  // a directory
  EXPECT_THROW(FileWindow(path("missing")), Error);
}

// What a reader gives for a file: the cloud, in words, or its error.
std::string described(const std::string& file) {
  try {
    const PointCloud c = read_point_cloud(file);
    std::string out = std::to_string(c.size()) + " points, origin " + std::to_string(c.origin.x) + "\n";
    char line[200];
    for (std::size_t i = 0; i < c.size(); ++i) {
      std::snprintf(line, sizeof line, "%.9g %.9g %.9g", double(c.positions[i].x), double(c.positions[i].y),
                    double(c.positions[i].z));
      out += line;
      if (c.has_normals()) out += " n " + std::to_string(c.normals[i].x) + " " + std::to_string(c.normals[i].z);
      if (c.has_colors()) out += " c " + std::to_string(int(c.colors[i].r)) + " " + std::to_string(int(c.colors[i].b));
      for (const ScalarProperty& s : c.scalars) out += " " + s.name + " " + std::to_string(s.values[i]);
      out += "\n";
    }
    return out + (c.mesh_vertices ? "mesh vertices\n" : "");
  } catch (const Error& e) {
    return std::string("error: ") + e.what();
  }
}

// Every prefix of `bytes` as a file, and the whole: the same cloud or the same message with
// windows of 1, 2, 3 and 7 bytes as with the default (which holds these files whole).
void FileWindowTest::expect_the_same_whatever_the_window(const std::string& name, const std::string& bytes) {
  int clouds = 0;
  for (std::size_t length = 0; length <= bytes.size(); ++length) {
    const std::string file = write(name, bytes.substr(0, length));
    FileWindow::set_default_window(std::size_t(1) << 20);
    const std::string whole = described(file);
    clouds += whole.rfind("error", 0) != 0;
    for (const std::size_t window : {1u, 2u, 3u, 7u}) {
      FileWindow::set_default_window(window);
      ASSERT_EQ(described(file), whole) << name << " cut at " << length << " of " << bytes.size() << ", window "
                                        << window;
    }
  }
  EXPECT_GT(clouds, 0) << name << ": no prefix is a cloud";
}

TEST_F(FileWindowTest, AsciiPlyWithCommentsListsAndCrlf) {
  expect_the_same_whatever_the_window(
      "a.ply",
      "ply\r\nformat ascii 1.0\r\ncomment a b\r\nelement camera 1\r\nproperty list uchar float k\r\n"
      "element vertex 3\r\nproperty float x\r\nproperty double y\r\nproperty float z\r\nproperty uchar red\r\n"
      "property uchar green\r\nproperty uchar blue\r\nproperty int label\r\nproperty list uchar int idx\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
      "2 0.5 1.5\r\n1 2 3 10 20 30 7 0\r\n+4.25   5e-1\r\n6 255 0 1 -8 2 1 2\r\n7 8 9 1 2 3 9 1 5\r\n3 0 1 2\r\n");
}

TEST_F(FileWindowTest, BinaryPlyOfEitherByteOrderWithNormalsScalarsAndFaces) {
  for (const bool big : {false, true}) {
    std::string b = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "property float nx\nproperty float ny\nproperty float nz\nproperty ushort quality\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 3; ++i) {
      for (const float v : {1.5f * float(i), -2.0f, 0.25f + float(i), 0.0f, 0.0f, 1.0f}) b += bytes_of(v, big);
      b += bytes_of(std::uint16_t(300 + i), big);
    }
    b += bytes_of(std::uint8_t(3), big) + bytes_of(0, big) + bytes_of(1, big) + bytes_of(2, big);
    expect_the_same_whatever_the_window(big ? "be.ply" : "le.ply", b);
  }
}

TEST_F(FileWindowTest, XyzWithCommentsBlankLinesAndNoFinalNewline) {
  expect_the_same_whatever_the_window("a.xyz",
                                      "# x y z nx ny nz\n1 2 3 0 0 1\r\n\n  4,5,6 1 0 0\n# end\n7 8 9 0 1 0");
  expect_the_same_whatever_the_window("b.xyz", "1e3 2 3\n4 5 6\n7 8 9\n");
}

TEST_F(FileWindowTest, LasWithColoursAfterAVariableLengthRecord) {
  expect_the_same_whatever_the_window("a.las", test::las_12_format_2(2, 10));
}

// Resident bytes now (Linux), for the read's cost beside it.
std::int64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::int64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * 4096;
}

// A read holds the cloud and a window, not the file as well: a 24 MB binary PLY of 2·10⁶
// points costs its 24 MB of positions (the whole file read first made it 48).
TEST_F(FileWindowTest, ReadingABinaryPlyHoldsItsPointsNotItsFile) {
  constexpr int n = 2'000'000;
  std::string b = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                  "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  b.reserve(b.size() + std::size_t(n) * 12);
  for (int i = 0; i < n; ++i)
    for (const float v : {float(i % 1000), float(i / 1000), 0.5f}) b += bytes_of(v);
  const std::string file = write("big.ply", b);
  b.clear();
  b.shrink_to_fit();
  watch_peak_memory(true);
  const std::int64_t before = resident_bytes();
  const int watch = begin_peak_watch();
  const PointCloud cloud = read_point_cloud(file);
  const std::int64_t peak = end_peak_watch(watch);
  watch_peak_memory(false);
  ASSERT_EQ(cloud.size(), std::size_t(n));
  if (peak < 0) GTEST_SKIP() << "this system does not tell the peak";
  const std::int64_t positions = std::int64_t(n) * 12;
  EXPECT_LT(peak - before, positions * 3 / 2) << "peak " << peak << ", before " << before;
}

}  // namespace
}  // namespace pss
