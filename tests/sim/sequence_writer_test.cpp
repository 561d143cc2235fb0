// Whole sequences on disk: TUM layout, readers accept it, determinism,
// and the static reference run differs only where the masks say.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "stillslam/core/error.h"
#include "stillslam/io/dataset.h"
#include "stillslam/io/camera_settings.h"
#include "stillslam/io/yaml_reader.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/sequence_writer.h"
#include "stillslam/sim/simulator.h"

namespace stillslam::sim {
namespace {
namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("stillslam_sim_" + name + "_" + std::to_string(std::random_device{}()));
  fs::remove_all(dir);
  return dir;
}

struct TempDir {
  explicit TempDir(const std::string& name) : path(temp_dir(name)) {}
  ~TempDir() { fs::remove_all(path); }
  fs::path path;
};

SimulationOptions tiny() {
  SimulationOptions o;
  o.width = 160;
  o.height = 120;
  o.frames = 6;
  o.people = 2;
  o.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  return o;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int count_lines(const fs::path& p, bool skip_comments) {
  std::ifstream in(p);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) n += !(line.empty() || (skip_comments && line[0] == '#'));
  return n;
}

TEST(SequenceWriter, WritesTumLayoutThatTheReadersLoad) {
  TempDir dir("layout");
  SimulationOptions o = tiny();
  o.trajectory = "walking_xyz";
  const SequenceSummary s = write_sequence(dir.path, o);
  ASSERT_EQ(s.frames, 6);
  EXPECT_EQ(count_lines(dir.path / "rgb.txt", true), 6);
  EXPECT_EQ(count_lines(dir.path / "depth.txt", true), 6);
  EXPECT_EQ(count_lines(dir.path / "associations.txt", false), 6);
  for (const char* sub : {"rgb", "depth", "masks", "instances"}) {
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path / sub), fs::directory_iterator{}), 6) << sub;
  }
  // First association line names files that exist, with equal stamps.
  std::ifstream assoc(dir.path / "associations.txt");
  std::string t1, rgb, t2, depth;
  assoc >> t1 >> rgb >> t2 >> depth;
  EXPECT_EQ(t1, t2);
  EXPECT_EQ(t1, "1341846313.637800");  // walking_xyz starts at its first ground-truth stamp
  const cv::Mat d = cv::imread((dir.path / depth).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(d.type(), CV_16UC1);
  EXPECT_EQ(d.size(), cv::Size(160, 120));
  EXPECT_GT(cv::countNonZero(d), 160 * 120 * 99 / 100);  // noise-free: depth everywhere

  // Ground truth: 6 poses; frame 0 is the TUM file's first pose.
  const Trajectory gt = read_trajectory(dir.path / "groundtruth.txt");
  ASSERT_EQ(gt.size(), 6u);
  EXPECT_NEAR(gt[0].T_world_cam.translation().x(), -0.6885, 1e-9);
  EXPECT_NEAR(gt[1].timestamp - gt[0].timestamp, 1.0 / 30, 1e-6);

  // io's camera settings and TUM reader accept the sequence as written.
  const CameraSettings settings = load_camera_settings(dir.path / "settings.yaml");
  EXPECT_NEAR(settings.camera.fx, 535.4 / 4, 1e-6);
  EXPECT_EQ(settings.camera.width, 160);
  EXPECT_DOUBLE_EQ(settings.depth_map_factor, 5000);
  EXPECT_TRUE(fs::path(YamlReader(dir.path / "settings.yaml").optional_string("Segmentation.model").value_or(""))
                  .is_absolute());
  const auto dataset = open_dataset(dir.path, settings);
  ASSERT_EQ(dataset->size(), 6u);
  EXPECT_EQ(dataset->kind(), "tum");
  const SensorFrame f = dataset->load(2);
  ASSERT_FALSE(f.depth.empty());
  // Depth round trip through the 16-bit PNG: 0.2 mm steps.
  const Simulator sim(o);
  const SimFrame ref = sim.render_frame(2);
  cv::Mat diff;
  cv::absdiff(f.depth, ref.depth, diff);
  double max_diff = 0;
  cv::minMaxLoc(diff, nullptr, &max_diff);
  EXPECT_LT(max_diff, 1.1e-4);

  // Instance ids: 16-bit, non-zero exactly where the mask is, each listed in instances.txt.
  EXPECT_EQ(count_lines(dir.path / "instances.txt", true), 2);  // two walking people
  const SimFrame first = sim.render_frame(0);  // `rgb` names frame 0
  const cv::Mat ids = cv::imread((dir.path / "instances" / fs::path(rgb).filename()).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(ids.type(), CV_16UC1);
  EXPECT_EQ(cv::countNonZero(ids != first.dynamic_ids), 0);
  EXPECT_EQ(cv::countNonZero(ids), cv::countNonZero(first.mask));
  std::ifstream instances(dir.path / "instances.txt");
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(instances, line)) {
    if (!line.empty() && line[0] != '#') rows.push_back(line);
  }
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], "1 walking_person person 1");
  EXPECT_EQ(rows[1], "2 walking_person person 1");

  // Writing again into the same folder needs overwrite, and leaves no stale frames.
  EXPECT_THROW(write_sequence(dir.path, o), Error);
  o.overwrite = true;
  o.frames = 4;
  EXPECT_EQ(write_sequence(dir.path, o).frames, 4);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path / "rgb"), fs::directory_iterator{}), 4);
}

TEST(SequenceWriter, SameSeedSameBytes) {
  TempDir a("det_a"), b("det_b");
  SimulationOptions o = tiny();
  o.frames = 3;
  o.noise = 1;
  o.trajectory = "halfsphere";
  write_sequence(a.path, o);
  write_sequence(b.path, o);
  int compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(a.path)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a.path);
    EXPECT_EQ(read_bytes(e.path()), read_bytes(b.path / rel)) << rel;
    ++compared;
  }
  EXPECT_EQ(compared, 3 * 4 + 6);  // rgb, depth, masks, instances per frame + 5 text files + settings
  // A different seed gives a different sequence.
  TempDir c("det_c");
  o.seed = 1;
  write_sequence(c.path, o);
  const auto first = *fs::directory_iterator(a.path / "rgb");
  EXPECT_NE(read_bytes(first.path()), read_bytes(c.path / "rgb" / first.path().filename()));
}

TEST(Simulator, NoPeopleDiffersOnlyInsideTheMasks) {
  SimulationOptions with = tiny();
  with.trajectory = "static";
  with.people = 3;
  with.frames = 90;
  SimulationOptions without = with;
  without.no_people = true;
  const Simulator a(with), b(without);
  int masked_frames = 0;
  for (int i = 0; i < a.frame_count(); i += 8) {
    const SimFrame fa = a.render_frame(i), fb = b.render_frame(i);
    EXPECT_EQ(fa.T_world_cam.matrix(), fb.T_world_cam.matrix());
    EXPECT_EQ(cv::countNonZero(fb.mask), 0);
    // Colour may also change on the anti-aliased ring just outside a mask, and
    // where a sub-pixel sliver of a cut-out (a finger) is caught by an
    // anti-aliasing ray but by no pixel centre.
    cv::Mat near_mask;
    cv::dilate(fa.mask, near_mask, cv::Mat::ones(5, 5, CV_8U));
    cv::Mat gray_a, gray_b, diff;
    cv::absdiff(fa.bgr, fb.bgr, diff);
    cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
    diff.setTo(0, near_mask);
    EXPECT_LE(cv::countNonZero(diff), 2) << "frame " << i;
    cv::Mat ddiff = fa.depth != fb.depth;
    ddiff.setTo(0, fa.mask);
    EXPECT_EQ(cv::countNonZero(ddiff), 0) << "frame " << i;
    masked_frames += cv::countNonZero(fa.mask) > 0;
  }
  // People do walk through the view.
  EXPECT_GE(masked_frames, 3);
}

TEST(Simulator, ImagesAreRichInCorners) {
  SimulationOptions o = tiny();
  o.width = 320;
  o.height = 240;
  o.frames = 1;
  o.people = 0;
  for (const char* traj : {"walking_xyz", "halfsphere", "rpy"}) {
    o.trajectory = traj;
    const Simulator sim(o);
    const SimFrame f = sim.render_frame(0);
    cv::Mat gray;
    cv::cvtColor(f.bgr, gray, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> kps;
    cv::FAST(gray, kps, 20, true);
    // Corners in at least 85% of a 8x6 grid: features wherever the camera looks.
    std::vector<int> cells(48, 0);
    for (const auto& k : kps) ++cells[static_cast<int>(k.pt.y * 6 / 240) * 8 + static_cast<int>(k.pt.x * 8 / 320)];
    const auto covered = std::count_if(cells.begin(), cells.end(), [](int c) { return c >= 3; });
    EXPECT_GT(kps.size(), 600u) << traj;
    EXPECT_GE(covered, 41) << traj;
  }
}

}  // namespace
}  // namespace stillslam::sim
