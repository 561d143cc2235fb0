// `stillslam run` on ROS 2 bags made from the EuRoC clip of ../shared
// (db3; MCAP zstd; MCAP lz4 with PNG images): the same trajectory as the
// folder input; a bag damaged in the middle still runs the frames before the
// damage and writes their trajectory; bad bags and topics are clear errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

#include "common/run_stillslam.h"
#include "stillslam/io/bag_folder_writer.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/sequence_writer.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

const fs::path kClip = fs::path(STILLSLAM_SHARED_DIR) / "data" / "euroc_V1_01_micro";
const std::string kTopics = " --topics /cam0/image_raw,/cam1/image_raw";
constexpr int kFrames = 40;

struct Scratch {
  Scratch() : path(fs::temp_directory_path() / ("stillslam_run_bag_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path path;
};

test::CommandRun run(const fs::path& input, const fs::path& out, const std::string& extra = kTopics) {
  return test::run_stillslam("run --config " + (fs::path(STILLSLAM_SOURCE_DIR) / "config" / "euroc.yaml").string() +
                                 " --input " + input.string() + " --output " + out.string() + extra +
                                 " --no-segmentation --deterministic --vocabulary none --max-frames " +
                                 std::to_string(kFrames),
                             true);
}

fs::path write_bag(const fs::path& out, const std::string& format, const std::string& compression,
                   const std::string& images) {
  BagFolderWriteOptions o;
  o.bag.format = format;
  o.bag.compression = compression;
  o.bag.chunk_size = 1 << 20;
  o.images = images;
  o.max_frames = kFrames;
  write_folder_as_bag(kClip, out, o);
  return out;
}

double max_position_difference(const Trajectory& a, const Trajectory& b) {
  double d = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    d = std::max(d, (a[i].T_world_cam.translation() - b[i].T_world_cam.translation()).norm());
  }
  return d;
}

TEST(RunBag, EurocClipAsBagsGivesTheFolderTrajectory) {
  REQUIRE_STILLSLAM_BINARY();
  if (!fs::exists(kClip)) GTEST_SKIP() << "EuRoC clip not found at " << kClip << " (../shared next to the repo)";
  Scratch dir;
  const auto folder = run(kClip, dir.path / "out_folder", "");
  ASSERT_EQ(folder.status, 0) << folder.out;
  const Trajectory expected = read_trajectory(dir.path / "out_folder" / "trajectory.txt");
  ASSERT_EQ(expected.size(), static_cast<std::size_t>(kFrames));
  struct Variant {
    std::string name, format, compression, images;
  };
  for (const Variant& v : {Variant{"db3_raw", "db3", "none", "raw"}, Variant{"zstd_raw.mcap", "mcap", "zstd", "raw"},
                           Variant{"lz4_png", "mcap", "lz4", "png"}}) {
    SCOPED_TRACE(v.name);
    const fs::path bag = write_bag(dir.path / v.name, v.format, v.compression, v.images);
    const auto r = run(bag, dir.path / ("out_" + v.name));
    ASSERT_EQ(r.status, 0) << r.out;
    const Trajectory got = read_trajectory(dir.path / ("out_" + v.name) / "trajectory.txt");
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].timestamp, expected[i].timestamp) << i;
    EXPECT_LT(max_position_difference(got, expected), 1e-3);
    EXPECT_EQ(max_position_difference(got, expected), 0.0);  // same pixels, same stamps: bit for bit
  }
}

TEST(RunBag, DamagedInTheMiddleRunsTheFramesBeforeAndBadInputIsAClearError) {
  REQUIRE_STILLSLAM_BINARY();
  if (!fs::exists(kClip)) GTEST_SKIP() << "EuRoC clip not found at " << kClip << " (../shared next to the repo)";
  Scratch dir;
  const fs::path bag = write_bag(dir.path / "damaged.mcap", "mcap", "zstd", "raw");
  {
    std::fstream f(bag, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(bag) / 2));
    const std::string junk(256, '\x5A');
    f.write(junk.data(), static_cast<std::streamsize>(junk.size()));
  }
  const auto r = run(bag, dir.path / "out_damaged");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("damaged"), std::string::npos) << r.out;
  const Trajectory t = read_trajectory(dir.path / "out_damaged" / "trajectory.txt");
  EXPECT_GT(t.size(), 5u);
  EXPECT_LT(t.size(), static_cast<std::size_t>(kFrames));

  // Truncated before the first message: an error naming the file and the byte.
  const fs::path truncated = dir.path / "truncated.mcap";
  fs::copy_file(bag, truncated);
  fs::resize_file(truncated, 300);
  auto e = run(truncated, dir.path / "out_truncated");
  EXPECT_NE(e.status, 0);
  EXPECT_NE(e.out.find(truncated.string() + ": at byte"), std::string::npos) << e.out;

  // A missing topic, and a single camera topic for stereo: the bag's topics are listed.
  e = run(bag, dir.path / "out_missing", " --topics /cam0/image_raw,/cam2/image_raw");
  EXPECT_NE(e.status, 0);
  EXPECT_NE(e.out.find("'/cam2/image_raw' is not in the bag"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("/cam1/image_raw (sensor_msgs/msg/Image"), std::string::npos) << e.out;
  e = run(bag, dir.path / "out_one", " --topics /cam0/image_raw");
  EXPECT_NE(e.status, 0);
  EXPECT_NE(e.out.find("stereo needs two"), std::string::npos) << e.out;
}

TEST(BagCommands, InfoAndExportOnTheRealMcap) {
  REQUIRE_STILLSLAM_BINARY();
  const fs::path mcap = fs::path(STILLSLAM_SHARED_DIR) / "data" / "trajectories" / "nav2_turtlebot.mcap";
  if (!fs::exists(mcap)) GTEST_SKIP() << "real bag not found at " << mcap << " (../shared next to the repo)";
  Scratch dir;
  const auto info = test::run_stillslam("bag-info " + mcap.string(), false);
  ASSERT_EQ(info.status, 0) << info.out;
  EXPECT_NE(info.out.find("/odom  nav_msgs/msg/Odometry  2639 messages"), std::string::npos) << info.out;
  const auto tf = test::run_stillslam("bag-export " + mcap.string() + " --topic /tf --frames odom,base_link --out " +
                                          (dir.path / "tf.txt").string(),
                                      true);
  ASSERT_EQ(tf.status, 0) << tf.out;
  EXPECT_EQ(read_trajectory(dir.path / "tf.txt").size(), 2639u);
  const auto no_frames = test::run_stillslam("bag-export " + mcap.string() + " --topic /tf --out " +
                                                 (dir.path / "x.txt").string(),
                                             true);
  EXPECT_NE(no_frames.status, 0);
  EXPECT_NE(no_frames.out.find("map,odom"), std::string::npos) << no_frames.out;
}

// A synthetic TUM RGB-D sequence written as a bag (PNG colour, compressedDepth
// PNG in millimetres) runs RGB-D and tracks as the folder does: depth in the bag
// is quantized to 1 mm (the folder's 0.2 mm), so the ATE is close, not equal.
TEST(RunBag, RgbdBagFromATumFolder) {
  REQUIRE_STILLSLAM_BINARY();
  Scratch dir;
  sim::SimulationOptions opts;
  opts.trajectory = "walking_xyz";
  opts.frames = 30;
  opts.width = 400;
  opts.height = 300;
  opts.no_people = true;
  opts.supersampling = 1;
  opts.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  const sim::SequenceSummary seq = sim::write_sequence(dir.path / "seq", opts);
  BagFolderWriteOptions o;
  o.bag.compression = "lz4";
  o.images = "png";
  const BagFolderWriteResult written = write_folder_as_bag(dir.path / "seq", dir.path / "rgbd_bag", o);
  EXPECT_EQ(written.layout, "tum");
  EXPECT_EQ(written.frames, 30u);
  const auto r = test::run_stillslam("run --config " + seq.settings.string() + " --input " +
                                         (dir.path / "rgbd_bag").string() +
                                         " --topics /camera/rgb/image_color,/camera/depth/image --output " +
                                         (dir.path / "out").string() + " --groundtruth " +
                                         (dir.path / "seq" / "groundtruth.txt").string() +
                                         " --no-segmentation --deterministic --vocabulary none",
                                     true);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("(rgbd)"), std::string::npos) << r.out;
  const Trajectory t = read_trajectory(dir.path / "out" / "trajectory.txt");
  EXPECT_EQ(t.size(), 30u);
  const auto ate = r.out.find("ATE rmse ");
  ASSERT_NE(ate, std::string::npos) << r.out;
  EXPECT_LT(std::stod(r.out.substr(ate + 9)), 0.01) << r.out;
}

}  // namespace
}  // namespace stillslam
