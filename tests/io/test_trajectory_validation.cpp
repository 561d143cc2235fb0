// Trajectory files that used to be read into wrong numbers: ambiguous csv,
// wrong column counts, absurd values, repeated stamps. Each must be an Error
// naming the file and line (or a warning for harmless duplicates).
#include <gtest/gtest.h>

#include <string>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/trajectory.h"
#include "common/error_text.h"

namespace stillslam {
namespace {

using test::contains;
using test::error_of;

namespace fs = std::filesystem;

// Two TUM poses whose quaternions read in the wrong order give other rotations.
constexpr const char* kTumLines = "1341846313.6378 1 2 3 0.1 0.2 0.3 0.9273618495495704\n"
                                  "1341846313.6678 1.1 2 3 0.2 0.1 0.3 0.9273618495495704\n";

std::string with_commas(std::string text) {
  for (char& c : text) {
    if (c == ' ') c = ',';
  }
  return text;
}

TEST(TrajectoryValidation, CsvWithoutHeaderIsAmbiguousAndNamesTheFlag) {
  test::TempDir dir;
  const fs::path csv = dir.write("tum_commas.txt", with_commas(kTumLines));
  const std::string message = error_of([&] { read_trajectory(csv); });
  EXPECT_TRUE(contains(message, csv.string() + ", line 1")) << message;
  EXPECT_TRUE(contains(message, "q_w first")) << message;
  EXPECT_TRUE(contains(message, "--est-format")) << message;
  EXPECT_THROW(detect_trajectory_format(csv), Error);

  // Given the format, the commas are only separators: the same poses as the blank-separated file.
  const Trajectory spaces = read_trajectory(dir.write("tum.txt", kTumLines));
  const Trajectory commas = read_trajectory(csv, TrajectoryFormat::Tum);
  ASSERT_EQ(commas.size(), 2u);
  EXPECT_EQ(commas[1].timestamp, spaces[1].timestamp);
  EXPECT_LT((commas[1].T_world_cam.matrix() - spaces[1].T_world_cam.matrix()).cwiseAbs().maxCoeff(), 1e-15);

  // A header naming the quaternion columns decides: x first is TUM, w first EuRoC.
  const fs::path tum_header = dir.write("tum_header.csv", "#timestamp,tx,ty,tz,qx,qy,qz,qw\n" + with_commas(kTumLines));
  EXPECT_EQ(detect_trajectory_format(tum_header), TrajectoryFormat::Tum);
  const Trajectory headed = read_trajectory(tum_header);
  EXPECT_LT((headed[1].T_world_cam.matrix() - spaces[1].T_world_cam.matrix()).cwiseAbs().maxCoeff(), 1e-15);
  const fs::path euroc_header = dir.write("euroc.csv", "#timestamp [ns],p_x,p_y,p_z,q_w,q_x,q_y,q_z\n"
                                                       "1403715274312143104,1,2,3,1,0,0,0\n");
  EXPECT_EQ(detect_trajectory_format(euroc_header), TrajectoryFormat::Euroc);
}

TEST(TrajectoryValidation, WrongColumnCountsNameTheExpectedCounts) {
  test::TempDir dir;
  // KITTI rows that lost a number: 11 fields are neither KITTI (12) nor TUM (8).
  const fs::path kitti11 = dir.write("kitti11.txt", "1 0 0 0 0 1 0 0 0 0 1\n1 0 0 0.1 0 1 0 0 0 0 1\n");
  std::string message = error_of([&] { read_trajectory(kitti11); });
  EXPECT_TRUE(contains(message, kitti11.string() + ", line 1")) << message;
  EXPECT_TRUE(contains(message, "found 11 fields")) << message;
  EXPECT_TRUE(contains(message, "12 (KITTI")) << message;
  EXPECT_TRUE(contains(message, "8 (TUM")) << message;
  message = error_of([&] { read_trajectory(kitti11, TrajectoryFormat::Kitti); });
  EXPECT_TRUE(contains(message, "line 1: expected 12 numbers")) << message;

  // TUM: 8 columns (9 in pyslam's files); a line with 10 is an error even after good lines.
  const fs::path tum10 = dir.write("tum10.txt", std::string(kTumLines) + "1341846313.6978 1 2 3 0 0 0 1 7 7\n");
  message = error_of([&] { read_trajectory(tum10); });
  EXPECT_TRUE(contains(message, "line 3: expected 8 (9 in pyslam's files) numbers")) << message;
  EXPECT_TRUE(contains(message, "found 10")) << message;

  // EuRoC: every line has the column count of the first pose line.
  const fs::path euroc = dir.write("cut.csv", "#timestamp,p_x,p_y,p_z,q_w,q_x,q_y,q_z,v_x,v_y,v_z\n"
                                              "1403715274312143104,1,2,3,1,0,0,0,0,0,0\n"
                                              "1403715274362142976,1,2,3,1,0,0,0,0\n");
  message = error_of([&] { read_trajectory(euroc); });
  EXPECT_TRUE(contains(message, "line 3: expected 11 (as the first pose line) numbers")) << message;
}

TEST(TrajectoryValidation, AbsurdValuesAreRejectedWithFileAndLine) {
  test::TempDir dir;
  const std::string good = "1.0 0 0 0 0 0 0 1\n";
  struct Case {
    std::string line, expected;
  };
  for (const Case& c : {Case{"2.0 1e300 0 0 0 0 0 1", "line 2: position (1e+300, 0, 0) is beyond 1e+08 m"},
                        Case{"2.0 0 0 0 0 0 0 1e300", "has length 1e+300, expected 1"},
                        Case{"2.0 0 0 0 0 0 0 2", "has length 2, expected 1"},
                        Case{"2.0 0 0 0 0 0 0 0", "has length 0, expected 1"},
                        Case{"1e300 0 0 0 0 0 0 1", "line 2: timestamp '1e300' is beyond 1e+10 s"},
                        Case{"2.0 0 nan 0 0 0 0 1", "'nan' is not a finite number"},
                        Case{"2.0 0 0 inf 0 0 0 1", "'inf' is not a finite number"},
                        Case{"5e11 0 0 0 0 0 0 1", "timestamp '5e11' is beyond 1e+10 s"}}) {
    const fs::path path = dir.write("absurd.txt", good + c.line + "\n");
    const std::string message = error_of([&] { read_trajectory(path); });
    EXPECT_TRUE(contains(message, path.string() + ", line 2")) << message;
    EXPECT_TRUE(contains(message, c.expected)) << c.line << " -> " << message;
  }
  // KITTI: the 3x3 part must be a rotation, the translation bounded.
  const fs::path scaled = dir.write("scaled.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n2 0 0 0 0 2 0 0 0 0 2 0\n");
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(scaled); }), "line 2: the 3x3 part is not a rotation matrix"));
  // A first pose line with a NaN stamp is an error, not a header to skip.
  const fs::path nan_first = dir.write("nan_first.txt", "nan 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0 1\n");
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(nan_first); }), "line 1: 'nan' is not a finite number"));
  const fs::path nan_csv = dir.write("nan_first.csv", "#t,x,y,z,qw,qx,qy,qz\nnan,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n");
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(nan_csv); }), "line 2: 'nan' is not a finite number"));
  const fs::path far = dir.write("far.txt", "1 0 0 0 0 1 0 0 0 0 1 3e9\n");
  EXPECT_TRUE(contains(error_of([&] { read_trajectory(far); }), "line 1: position (0, 0, 3e+09) is beyond 1e+08 m"));
  // Georeferenced positions (UTM: 5.4e6 m northing) are real trajectories.
  EXPECT_EQ(read_trajectory(dir.write("utm.txt", "1.0 458074.6 5429380.2 162.9 0 0 0 1\n")).size(), 1u);
}

TEST(TrajectoryValidation, RepeatedStamps) {
  test::TempDir dir;
  // Same stamp, different pose: the file contradicts itself.
  const fs::path conflict = dir.write("conflict.txt", "# t x y z qx qy qz qw\n"
                                                      "1.0 0 0 0 0 0 0 1\n"
                                                      "2.0 1 0 0 0 0 0 1\n"
                                                      "1.0 5 0 0 0 0 0 1\n");
  const std::string message = error_of([&] { read_trajectory(conflict, {}, DuplicateStamps::Error); });
  EXPECT_TRUE(contains(message, conflict.string() + ", lines 2 and 4: the same timestamp 1 s")) << message;
  EXPECT_TRUE(contains(message, "--duplicate-stamps last")) << message;
  const Trajectory last = read_trajectory(conflict);  // KeepLast, the default
  ASSERT_EQ(last.size(), 2u);
  EXPECT_EQ(last[0].timestamp, 2.0);
  EXPECT_EQ(last[1].T_world_cam.translation().x(), 5.0);  // line 4 won

  // Same stamp, same pose: kept once (with a warning).
  const fs::path repeated = dir.write("repeated.txt", "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n");
  const Trajectory once = read_trajectory(repeated);
  ASSERT_EQ(once.size(), 2u);
  EXPECT_EQ(once[1].timestamp, 2.0);

  // KITTI stamps from a times file: the lines named are the times file's.
  const fs::path poses = dir.write("poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n");
  const fs::path times = dir.write("times.txt", "0.5\n0.5\n");
  const std::string kitti = error_of([&] { read_kitti_trajectory(poses, times, DuplicateStamps::Error); });
  EXPECT_TRUE(contains(kitti, "KITTI times file " + times.string())) << kitti;
  EXPECT_TRUE(contains(kitti, "lines 1 and 2")) << kitti;
}

}  // namespace
}  // namespace stillslam
