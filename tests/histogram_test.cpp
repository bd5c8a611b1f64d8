// Histograms and suggested iso-values: synthetic volumes of known materials (plateaus of
// known values plus noise) whose valleys must fall between the plateaus; the shipped scans,
// where the suggestions must separate what a user would separate; and `pss info` on volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "pss/io/volume_file.hpp"
#include "pss/volume/histogram.hpp"
#include "support/cli.hpp"

namespace pss {
namespace {

// `count` voxels: each of `levels` takes its share, plus Gaussian noise of `sigma`; rounded
// and clamped to 0..255 when `quantise` (8-bit scans).
std::vector<float> plateaus(const std::vector<std::pair<float, double>>& levels, float sigma, bool quantise,
                            int count = 200000) {
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, sigma);
  std::vector<float> v;
  for (const auto& [value, share] : levels)
    for (int i = 0; i < int(share * count); ++i) {
      float x = value + (sigma > 0 ? noise(rng) : 0.0f);
      if (quantise) x = std::clamp(std::round(x), 0.0f, 255.0f);
      v.push_back(x);
    }
  std::shuffle(v.begin(), v.end(), rng);
  return v;
}

TEST(Histogram, StatsAndBins) {
  const std::vector<float> v = {0, 1, 2, 3, 4, 5, 6, 7, 8, 10};
  const ValueStats s = value_stats(v);
  EXPECT_EQ(s.count, 10);
  EXPECT_EQ(s.min, 0.0f);
  EXPECT_EQ(s.max, 10.0f);
  EXPECT_DOUBLE_EQ(s.mean, 4.6);
  const Histogram h = make_histogram(v, 5, 0, 10);
  EXPECT_EQ(h.counts, (std::vector<std::int64_t>{2, 2, 2, 2, 2}));  // the top edge falls in the last bin
  EXPECT_DOUBLE_EQ(h.center(0), 1.0);
  EXPECT_EQ(h.total(), 10);
  // Integers spanning few values: one bin per integer, centred on it.
  const Histogram f = fine_histogram(v, s);
  EXPECT_EQ(f.bins(), 11);
  EXPECT_DOUBLE_EQ(f.center(4), 4.0);
  EXPECT_EQ(f.counts[9], 0);
  // Fractions: the full 256 bins over [min, max].
  const std::vector<float> w = {0.5f, 1.25f, 3.0f};
  EXPECT_EQ(fine_histogram(w, value_stats(w)).bins(), 256);
}

TEST(Histogram, TwoMaterialsFloat) {
  const std::vector<float> v = plateaus({{20.0f, 0.6}, {180.0f, 0.4}}, 5.0f, false);
  const auto iso = suggest_iso_values(v);
  ASSERT_EQ(iso.size(), 1u);
  EXPECT_GT(iso[0].iso, 20 + 3 * 5.0f);
  EXPECT_LT(iso[0].iso, 180 - 3 * 5.0f);
  EXPECT_NEAR(iso[0].lower_peak, 20.0f, 2.0f);
  EXPECT_NEAR(iso[0].upper_peak, 180.0f, 2.0f);
  EXPECT_NEAR(iso[0].lower_share, 0.6, 0.01);
  EXPECT_NEAR(iso[0].upper_share, 0.4, 0.01);
  EXPECT_FALSE(iso[0].tail);
}

TEST(Histogram, ThreeMaterials8BitWithATinyFourth) {
  // Air, tissue, bone; and 0.5 % of something at 250: too few voxels to be a material.
  const std::vector<float> v = plateaus({{10.0f, 0.5}, {100.0f, 0.3}, {200.0f, 0.195}, {250.0f, 0.005}}, 6.0f, true);
  const auto iso = suggest_iso_values(v);
  ASSERT_EQ(iso.size(), 2u);
  EXPECT_GT(iso[0].iso, 10 + 3 * 6.0f);
  EXPECT_LT(iso[0].iso, 100 - 3 * 6.0f);
  EXPECT_GT(iso[1].iso, 100 + 3 * 6.0f);
  EXPECT_LT(iso[1].iso, 200 - 3 * 6.0f);
}

TEST(Histogram, GapIsSplitInItsMiddleAndConstantHasNone) {
  const std::vector<float> v = plateaus({{0.0f, 0.5}, {100.0f, 0.5}}, 0.0f, true, 1000);
  const auto iso = suggest_iso_values(v);
  ASSERT_EQ(iso.size(), 1u);
  EXPECT_NEAR(iso[0].iso, 50.0f, 1.0f);
  EXPECT_TRUE(suggest_iso_values(std::vector<float>(100, 3.0f)).empty());
  EXPECT_TRUE(suggest_iso_values(std::vector<float>{}).empty());
}

TEST(Histogram, OnePeakWithATailSuggestsItsFoot) {
  // 95 % background near 2 and 5 % decaying away from it (a plume thinning into air): no
  // second hump, and no valley.
  std::vector<float> v = plateaus({{2.0f, 0.95}}, 1.0f, true);
  std::mt19937 rng(3);
  std::exponential_distribution<float> decay(1.0f / 40.0f);
  for (int i = 0; i < 10000; ++i) v.push_back(std::min(255.0f, std::round(3.0f + decay(rng))));
  const auto iso = suggest_iso_values(v);
  ASSERT_EQ(iso.size(), 1u);
  EXPECT_TRUE(iso[0].tail);
  EXPECT_GT(iso[0].iso, 3.0f);
  EXPECT_LT(iso[0].iso, 30.0f);
  EXPECT_GT(iso[0].upper_share, 0.03);
  EXPECT_LT(iso[0].upper_share, 0.06);
}

Volume shipped(const std::string& name, ivec3 dims) {
  const std::filesystem::path p = std::filesystem::path(PSS_SOURCE_DIR) / "data" / name;
  if (dims.x == 0) return read_volume(p, std::nullopt);
  RawVolumeFormat f;
  f.dims = dims;
  return read_volume(p, f);
}

// The scans: a suggestion between background and tooth (background 70..90, dentine ~160),
// between air and metal in the engine (50..100), the plume's edge in the fuel.
TEST(Histogram, ShippedScans) {
  const auto tooth = suggest_iso_values(shipped("tooth_103x94x161_uint8.raw", {103, 94, 161}).values);
  ASSERT_GE(tooth.size(), 1u);
  EXPECT_GT(tooth[0].iso, 95.0f);
  EXPECT_LT(tooth[0].iso, 150.0f);
  const auto engine = suggest_iso_values(shipped("engine_256x256x128_uint8.nrrd", {0, 0, 0}).values);
  ASSERT_GE(engine.size(), 1u);
  EXPECT_GE(engine[0].iso, 50.0f);
  EXPECT_LE(engine[0].iso, 100.0f);
  const auto fuel = suggest_iso_values(shipped("fuel_64x64x64_uint8.raw", {64, 64, 64}).values);
  ASSERT_EQ(fuel.size(), 1u);
  EXPECT_GT(fuel[0].iso, 0.0f);
  EXPECT_LT(fuel[0].iso, 30.0f);
}

TEST(Histogram, CliInfoOnVolumes) {
  const std::string tooth = std::string(PSS_SOURCE_DIR) + "/data/tooth_103x94x161_uint8.raw";
  const test::CliResult r = test::run_pss("info " + tooth + " --dims 103x94x161 --spacing 1,1,2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* expected : {"103 x 94 x 161", "uint8", "1 x 1 x 2", "[0, 255]", "suggested iso   1", "#"})
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << " in\n" << r.out;
  const test::CliResult e = test::run_pss("info " + std::string(PSS_SOURCE_DIR) + "/data/engine_256x256x128_uint8.nrrd");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("NRRD (compressed)"), std::string::npos) << e.out;
  // A lying header: one line naming the file, non-zero exit, nothing on stdout.
  const std::filesystem::path lie =
      std::filesystem::temp_directory_path() / ("pss-info-lie-" + std::to_string(::getpid()) + ".mha");
  std::ofstream(lie, std::ios::binary) << "NDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\nElementDataFile = LOCAL\n"
                                       << std::string(100, '\0');
  const test::CliResult l = test::run_pss("info " + lie.string());
  std::filesystem::remove(lie);
  EXPECT_NE(l.exit_code, 0);
  EXPECT_EQ(test::line_count(l.err), 1) << l.err;
  EXPECT_NE(l.err.find(lie.filename().string()), std::string::npos) << l.err;
  EXPECT_TRUE(l.out.empty()) << l.out;
  // --skip without --dims.
  const test::CliResult d = test::run_pss("info " + tooth + " --skip 4");
  EXPECT_NE(d.exit_code, 0);
  EXPECT_NE(d.err.find("--dims"), std::string::npos) << d.err;
}

}  // namespace
}  // namespace pss
