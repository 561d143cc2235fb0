#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/temp_dir.h"
#include "stillslam/io/timestamp_association.h"
#include "stillslam/io/tum_dataset.h"

namespace stillslam {
namespace {

using test::TempDir;

TEST(TimestampAssociation, GreedyUniqueWithinTolerance) {
  // b[1] is closest to both a[0] and a[1]: it goes to a[1] (smaller |dt|),
  // a[0] then takes b[0]; a[2] has nothing within 0.02 s; a[3] takes the
  // nearer of two candidates.
  const std::vector<double> a{1.000, 1.020, 2.000, 3.000};
  const std::vector<double> b{0.985, 1.012, 2.5, 3.0199, 3.001};
  const auto m = associate_timestamps(a, b, 0.02);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0], (std::pair<std::size_t, std::size_t>{0, 0}));
  EXPECT_EQ(m[1], (std::pair<std::size_t, std::size_t>{1, 1}));
  EXPECT_EQ(m[2], (std::pair<std::size_t, std::size_t>{3, 4}));
  EXPECT_TRUE(associate_timestamps({}, b, 0.02).empty());
  // Strictly less than max_dt, as associate.py.
  EXPECT_TRUE(associate_timestamps({1.0}, {1.5}, 0.5).empty());
  EXPECT_EQ(associate_timestamps({1.0}, {1.4}, 0.5).size(), 1u);
}

TEST(TimestampAssociation, UnsortedInputs) {
  const auto m = associate_timestamps({3.0, 1.0, 2.0}, {2.001, 0.999, 3.002}, 0.02);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0], (std::pair<std::size_t, std::size_t>{0, 2}));
  EXPECT_EQ(m[1], (std::pair<std::size_t, std::size_t>{1, 1}));
  EXPECT_EQ(m[2], (std::pair<std::size_t, std::size_t>{2, 0}));
}

std::filesystem::path frame_list(const std::string& name, const std::string& set = "tum") {
  return std::filesystem::path(STILLSLAM_SHARED_DIR) / "data" / "frame_lists" / set / name;
}

// The DynaSLAM / DANI-SLAM lists are associate.py output for the real TUM fr3
// and Bonn RGB-D Dynamic sequences. Splitting one back into rgb.txt/depth.txt (plus unmatched
// distractor frames) and re-associating must reproduce it exactly.
TEST(TimestampAssociation, ReproducesRealTumFrameLists) {
  if (!std::filesystem::exists(frame_list("fr3_walking_xyz.txt"))) {
    GTEST_SKIP() << "shared data not found at " << STILLSLAM_SHARED_DIR << " (../shared next to the repo)";
  }
  struct Expected {
    const char* set;
    const char* name;
    std::size_t count;
  };
  for (const Expected& e :
       {Expected{"tum", "fr3_walking_xyz.txt", 827}, Expected{"tum", "fr3_walking_static.txt", 717},
        Expected{"tum", "fr3_walking_rpy.txt", 866}, Expected{"tum", "fr3_walking_halfsphere.txt", 1021},
        Expected{"tum", "fr3_sitting_static.txt", 680}, Expected{"tum", "fr3_sitting_xyz.txt", 1219},
        Expected{"bonn", "rgbd_bonn_crowd.txt", 927}, Expected{"bonn", "rgbd_bonn_person2.txt", 567}}) {
    SCOPED_TRACE(e.name);
    const auto reference = read_tum_associations(frame_list(e.name, e.set));
    ASSERT_EQ(reference.size(), e.count);

    TempDir dir;
    std::ofstream rgb(dir.path() / "rgb.txt"), depth(dir.path() / "depth.txt");
    rgb << "# color images\n# file: 'rgbd_dataset_freiburg3'\n# timestamp filename\n";
    depth << "# depth maps\n# file: 'rgbd_dataset_freiburg3'\n# timestamp filename\n";
    rgb.precision(6);
    depth.precision(6);
    for (const TumPair& p : reference) {
      rgb << std::fixed << p.rgb_time << " " << p.rgb_file << "\n";
      depth << std::fixed << p.depth_time << " " << p.depth_file << "\n";
    }
    // A depth frame 25 ms after the last rgb frame: outside 0.02 s, unmatched.
    depth << std::fixed << reference.back().rgb_time + 0.025 << " depth/extra.png\n";
    rgb.close();
    depth.close();
    const auto pairs = associate_tum_lists(dir.path() / "rgb.txt", dir.path() / "depth.txt", 0.02);
    ASSERT_EQ(pairs.size(), reference.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      ASSERT_EQ(pairs[i].rgb_file, reference[i].rgb_file) << i;
      ASSERT_EQ(pairs[i].depth_file, reference[i].depth_file) << i;
    }
  }
}

TEST(TimestampAssociation, RealListContents) {
  if (!std::filesystem::exists(frame_list("fr3_walking_xyz.txt"))) {
    GTEST_SKIP() << "shared data not found at " << STILLSLAM_SHARED_DIR << " (../shared next to the repo)";
  }
  const auto pairs = read_tum_associations(frame_list("fr3_walking_xyz.txt"));
  ASSERT_EQ(pairs.size(), 827u);
  EXPECT_DOUBLE_EQ(pairs.front().rgb_time, 1341846313.592026);
  EXPECT_EQ(pairs.front().rgb_file, "rgb/1341846313.592026.png");
  EXPECT_DOUBLE_EQ(pairs.front().depth_time, 1341846313.592088);
  EXPECT_EQ(pairs.front().depth_file, "depth/1341846313.592088.png");
  EXPECT_EQ(pairs[2].depth_file, "depth/1341846313.686172.png");
  EXPECT_EQ(pairs.back().rgb_file, "rgb/1341846342.416195.png");
  EXPECT_EQ(pairs.back().depth_file, "depth/1341846342.416211.png");
  double max_dt = 0;
  for (const auto& p : pairs) max_dt = std::max(max_dt, std::abs(p.rgb_time - p.depth_time));
  EXPECT_LT(max_dt, 0.02);
}

}  // namespace
}  // namespace stillslam
