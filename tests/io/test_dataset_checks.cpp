// What open_dataset checks before any frame is read: the stamps of every list,
// lists of unequal length, the sensor the settings ask for against the folder,
// and a KITTI calib.txt against the settings' calibration.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "common/log_capture.h"
#include "io/dataset_fixtures.h"
#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/euroc_dataset.h"
#include "common/error_text.h"

namespace stillslam {
namespace {

using test::contains;
using test::error_of;

using test::TempDir;
namespace fs = std::filesystem;

std::vector<std::string> read_lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void write_lines(const fs::path& file, const std::vector<std::string>& lines) {
  std::ofstream out(file);
  for (const std::string& line : lines) out << line << "\n";
}

// Replaces the first field (up to `separator`, or the whole line) of 1-based line `line`.
void set_stamp(const fs::path& file, std::size_t line, const std::string& stamp, char separator = ' ') {
  auto lines = read_lines(file);
  std::string& l = lines.at(line - 1);
  const std::size_t end = l.find(separator);
  l = stamp + (end == std::string::npos ? "" : l.substr(end));
  write_lines(file, lines);
}

CameraSettings tum_settings() {
  CameraSettings s;
  s.camera.fx = s.camera.fy = 525;
  s.camera.cx = 32;
  s.camera.cy = 24;
  return s;
}

CameraSettings rgbd_settings() {
  CameraSettings s = tum_settings();
  s.file = "rgbd.yaml";
  s.rgbd = true;
  return s;
}

CameraSettings stereo_settings() {
  CameraSettings s = tum_settings();
  s.file = "stereo.yaml";
  StereoCalibration stereo;
  stereo.left = stereo.right = s.camera;
  stereo.baseline = 0.1;
  stereo.rectified = true;
  s.stereo = stereo;
  s.bf = 0.1 * s.camera.fx;
  return s;
}

struct BadStamp {
  std::string stamp;
  std::string expected;
};

// rgb.txt has 3 comment lines; frame k is on line 4 + k (stamps 100 + k/30).
const std::vector<BadStamp> kBadTumStamps = {
    {"nan", "rgb.txt:5: timestamp 'nan' is not a finite number"},
    {"inf", "rgb.txt:5: timestamp 'inf' is not a finite number"},
    {"-100.033333", "rgb.txt:5: timestamp '-100.033333' is negative"},
    {"99.5", "rgb.txt:5: timestamp '99.5' is earlier than the stamp '100.000000' on line 4"},
    {"100.000000", "rgb.txt:5: timestamp '100.000000' repeats the stamp '100.000000' on line 4"},
};

TEST(DatasetChecks, TumListStampsMustBeFiniteSortedAndUnique) {
  for (const BadStamp& bad : kBadTumStamps) {
    TempDir dir;
    const fs::path seq = test::write_tum_fixture(dir.path(), 3);
    set_stamp(seq / "rgb.txt", 5, bad.stamp);
    const std::string m = error_of([&] { open_dataset(seq, tum_settings()); });
    EXPECT_TRUE(contains(m, bad.expected)) << m;
    if (bad.expected.find("line 4") != std::string::npos) {
      EXPECT_TRUE(contains(m, "sort")) << m;
    }
  }
  // depth.txt is checked the same way.
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 3);
  set_stamp(seq / "depth.txt", 5, "100.004000");
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, tum_settings()); }),
                       "depth.txt:5: timestamp '100.004000' repeats the stamp '100.004000' on line 4"));
}

TEST(DatasetChecks, TumAssociationStampsAreChecked) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 3);
  write_lines(seq / "associations.txt", {"100.000000 rgb/a.png 100.004 depth/a.png",
                                         "100.033333 rgb/b.png 100.037 depth/b.png",
                                         "100.033333 rgb/c.png 100.071 depth/c.png"});
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, tum_settings()); }),
                       "associations.txt:3: rgb timestamp '100.033333' repeats the stamp '100.033333' on line 2"));
  // Depth first, as some tools write it: the rgb column is still the one sorted.
  write_lines(seq / "associations.txt", {"100.004 depth/a.png 100.000000 rgb/a.png",
                                         "100.037 depth/b.png 99.0 rgb/b.png"});
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, tum_settings()); }),
                       "associations.txt:2: rgb timestamp '99.0' is earlier than the stamp '100.000000' on line 1"));
  write_lines(seq / "associations.txt", {"100.000000 rgb/a.png nan depth/a.png"});
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, tum_settings()); }),
                       "associations.txt:1: depth timestamp 'nan' is not a finite number"));
}

TEST(DatasetChecks, EurocAndKittiStampsAreChecked) {
  TempDir dir;
  const fs::path seq = test::write_euroc_fixture(dir.path(), 3);
  const fs::path cam0 = seq / "mav0" / "cam0" / "data.csv";
  // The list has a header line; frame k is on line 2 + k.
  const std::string first = read_lines(cam0)[1].substr(0, 19);
  set_stamp(cam0, 3, first, ',');
  std::string m = error_of([&] { open_dataset(seq, tum_settings()); });
  EXPECT_TRUE(contains(m, "cam0/data.csv:3: timestamp [ns] '" + first + "' repeats the stamp '" + first +
                              "' on line 2"))
      << m;
  set_stamp(cam0, 3, "-5", ',');
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, tum_settings()); }),
                       "cam0/data.csv:3: timestamp [ns] '-5' is negative"));
  set_stamp(cam0, 2, std::to_string(std::stoll(first) + 60000000), ',');  // after line 3's
  set_stamp(cam0, 3, first, ',');
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, tum_settings()); }),
                       "cam0/data.csv:3: timestamp [ns] '" + first + "' is earlier than"));

  const fs::path kitti = test::write_kitti_fixture(dir.path(), 3, true);
  set_stamp(kitti / "times.txt", 2, "nan");
  EXPECT_TRUE(contains(error_of([&] { open_dataset(kitti, CameraSettings{}); }),
                       "times.txt:2: timestamp 'nan' is not a finite number"));
  write_lines(kitti / "times.txt", {"0.0", "0.2", "0.1"});
  EXPECT_TRUE(contains(error_of([&] { open_dataset(kitti, CameraSettings{}); }),
                       "times.txt:3: timestamp '0.1' is earlier than the stamp '0.2' on line 2"));
}

TEST(DatasetChecks, ShortCam1ListWarnsHowManyFramesAreDropped) {
  TempDir dir;
  const fs::path seq = test::write_euroc_fixture(dir.path(), 5);
  const fs::path cam1 = seq / "mav0" / "cam1" / "data.csv";
  auto lines = read_lines(cam1);
  lines.resize(3);  // header and two frames
  write_lines(cam1, lines);
  test::LogCapture log;
  const auto d = open_dataset(seq, tum_settings());
  EXPECT_EQ(d->size(), 2u);
  const std::string w = log.text();
  EXPECT_TRUE(contains(w, "cam0/data.csv lists 5 images and ")) << w;
  EXPECT_TRUE(contains(w, "cam1/data.csv lists 2: 2 stereo pairs within 0.02 s, 3 cam0 and 0 cam1 images "
                          "without a partner are dropped"))
      << w;
}

TEST(DatasetChecks, EqualListsGiveNoPairingWarning) {
  TempDir dir;
  const fs::path seq = test::write_euroc_fixture(dir.path(), 3);
  test::LogCapture log;
  EXPECT_EQ(open_dataset(seq, tum_settings())->size(), 3u);
  EXPECT_FALSE(contains(log.text(), "dropped")) << log.text();
}

TEST(DatasetChecks, TumRgbWithoutDepthWarns) {
  TempDir dir;
  const fs::path seq = test::write_tum_fixture(dir.path(), 4);  // the fifth rgb frame has no depth
  test::LogCapture log;
  EXPECT_EQ(open_dataset(seq, tum_settings())->size(), 4u);
  EXPECT_TRUE(contains(log.text(), "rgb.txt lists 5 images and ")) << log.text();
  EXPECT_TRUE(contains(log.text(), "depth.txt lists 4: 4 rgb/depth pairs within 0.02 s, 1 rgb images without a "
                                   "depth partner are dropped"))
      << log.text();
}

TEST(DatasetChecks, SettingsSensorMustMatchTheFolder) {
  TempDir dir;
  const fs::path euroc = test::write_euroc_fixture(dir.path() / "euroc", 2);
  std::string m = error_of([&] { open_dataset(euroc, rgbd_settings()); });
  EXPECT_TRUE(contains(m, "a EuRoC stereo folder, but the settings rgbd.yaml describe an RGB-D camera")) << m;
  EXPECT_TRUE(contains(m, "Stereo.T_c1_c2")) << m;
  const fs::path kitti = test::write_kitti_fixture(dir.path() / "kitti", 2, true);
  m = error_of([&] { open_dataset(kitti, rgbd_settings()); });
  EXPECT_TRUE(contains(m, "a KITTI stereo folder, but the settings rgbd.yaml describe an RGB-D camera")) << m;
  const fs::path tum = test::write_tum_fixture(dir.path() / "tum", 2);
  m = error_of([&] { open_dataset(tum, stereo_settings()); });
  EXPECT_TRUE(contains(m, "a TUM RGB-D folder, but the settings stereo.yaml describe a stereo pair")) << m;
  EXPECT_TRUE(contains(m, "RGBD.DepthMapFactor")) << m;
  m = error_of([&] { open_dataset(tum / "rgb.txt", stereo_settings()); });
  EXPECT_TRUE(contains(m, "describe a stereo pair")) << m;
  // Agreeing settings, and settings that say neither, open as before.
  EXPECT_EQ(open_dataset(tum, rgbd_settings())->kind(), "tum");
  EXPECT_EQ(open_dataset(euroc, tum_settings())->kind(), "euroc");
  EXPECT_EQ(open_dataset(kitti, CameraSettings{})->kind(), "kitti");
}

TEST(DatasetChecks, KittiCalibMustAgreeWithTheSettings) {
  TempDir dir;
  const fs::path seq = test::write_kitti_fixture(dir.path(), 2, true);  // sequence 00's calib.txt
  const fs::path config = fs::path(STILLSLAM_SOURCE_DIR) / "config";
  const std::string m = error_of([&] { open_dataset(seq, load_camera_settings(config / "kitti_04-12.yaml")); });
  EXPECT_TRUE(contains(m, "calib.txt: gives fx 718.856 but ")) << m;
  EXPECT_TRUE(contains(m, "kitti_04-12.yaml say 707.0912 (Camera.fx / Camera1.fx)")) << m;
  CameraSettings shifted = load_camera_settings(config / "kitti_00-02.yaml");
  shifted.bf *= 1.01;
  EXPECT_TRUE(contains(error_of([&] { open_dataset(seq, shifted); }), "calib.txt: gives bf 386.1448 but"));
  // The settings made for the sequence agree.
  const auto s = open_dataset(seq, load_camera_settings(config / "kitti_00-02.yaml"))->rectified_stereo();
  ASSERT_TRUE(s.has_value());
  EXPECT_DOUBLE_EQ(s->left.fx, 718.856);
}

}  // namespace
}  // namespace stillslam
