// Every reader that opens a text file: a folder, a missing path and a leading
// UTF-8 byte order mark get the same treatment (io/input_file.h).
#include <gtest/gtest.h>

#include <string>

#include <unistd.h>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/camera_settings.h"
#include "stillslam/io/input_file.h"
#include "stillslam/io/text_table.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/io/yaml_reader.h"
#include "common/error_text.h"

namespace stillslam {
namespace {

using test::contains;
using test::error_of;

namespace fs = std::filesystem;

const std::string kBom = "\xEF\xBB\xBF";

TEST(InputFile, FolderAndMissingPathAreNamed) {
  test::TempDir dir;
  const fs::path folder = dir.path() / "a_folder.txt";
  fs::create_directories(folder);
  const std::string expected = folder.string() + " is a folder, expected a file";
  EXPECT_TRUE(contains(error_of([&] { open_input_file(folder, "image list"); }), "image list " + expected));
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(folder); }), "trajectory file " + expected));
  EXPECT_TRUE(contains(error_of([&] { read_text_table(folder); }), expected));
  EXPECT_TRUE(contains(error_of([&] { YamlReader{folder}; }), "settings file " + expected));
  EXPECT_TRUE(contains(error_of([&] { load_camera_settings(folder); }), expected));
  EXPECT_TRUE(contains(error_of([&] { read_kitti_trajectory(dir.write("k.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n"), folder); }),
                       "KITTI times file " + expected));
  const fs::path missing = dir.path() / "missing.txt";
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(missing); }), missing.string() + " does not exist"));
  EXPECT_TRUE(contains(error_of([&] { read_text_table(missing); }), missing.string() + " does not exist"));
}

TEST(InputFile, UnreadableFileNamesThePermission) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads every file: no permission error to provoke";
  test::TempDir dir;
  const fs::path locked = dir.write("locked.txt", "1.0 0 0 0 0 0 0 1\n");
  fs::permissions(locked, fs::perms::none);
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(locked); }),
                       "trajectory file " + locked.string() + " cannot be read: permission denied"));
  fs::permissions(locked, fs::perms::owner_all);
}

TEST(InputFile, LeadingByteOrderMarkIsSkipped) {
  test::TempDir dir;
  EXPECT_EQ(read_input_file(dir.write("bom.txt", kBom + "text\n"), "file"), "text\n");
  EXPECT_EQ(read_input_file(dir.write("plain.txt", "te"), "file"), "te");  // shorter than a BOM

  const Trajectory t = read_trajectory(dir.write("bom_traj.txt", kBom + "1341846313.6378 1 2 3 0 0 0 1\n"));
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].timestamp, 1341846313.6378);
  const fs::path csv = dir.write("bom.csv", kBom + "#timestamp [ns],p_x,p_y,p_z,q_w,q_x,q_y,q_z\n"
                                                   "1403715274312143104,1,2,3,1,0,0,0\n");
  EXPECT_EQ(detect_trajectory_format(csv), TrajectoryFormat::Euroc);

  const auto rows = read_text_table(dir.write("rgb.txt", kBom + "1341846313.6378 rgb/1.png\n"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(parse_double(rows[0].fields[0], "rgb.txt", rows[0].line), 1341846313.6378);

  const YamlReader yaml(dir.write("bom.yaml", kBom + "%YAML:1.0\nCamera.fx: 517.5\n"));
  EXPECT_EQ(yaml.number("Camera.fx"), 517.5);
}

}  // namespace
}  // namespace stillslam
