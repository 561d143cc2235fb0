// io/yaml_reader: matrices with absurd shapes are an Error naming the key
// (no int overflow, no huge allocation), and the missing-row-comma repair of
// ORB-SLAM3 files works on any file size (found by fuzz_euroc_sensor).
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "io/temp_dir.h"
#include "stillslam/core/error.h"
#include "stillslam/io/yaml_reader.h"

namespace stillslam {
namespace {

std::string matrix_error(const test::TempDir& dir, const std::string& rows, const std::string& cols) {
  const auto file = dir.write("m.yaml", "%YAML:1.0\nT:\n  rows: " + rows + "\n  cols: " + cols + "\n  data: [1.0]\n");
  try {
    YamlReader(file).optional_matrix("T");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(YamlReader, MatrixShapesThatCannotBeAreErrors) {
  test::TempDir dir;
  // rows * cols is past int: compared as a size, not overflowed.
  EXPECT_NE(matrix_error(dir, "65536", "65536").find("m.yaml: key 'T' has 1 data values but rows*cols = 4294967296"),
            std::string::npos);
  for (const char* bad : {"1e300", "2.5", "1000001", ".nan"}) {
    EXPECT_NE(matrix_error(dir, bad, "1").find("m.yaml: key 'T' must have whole 'rows' and 'cols' up to 1000000"),
              std::string::npos)
        << bad;
  }
  EXPECT_EQ(matrix_error(dir, "1", "1"), "");
}

// OpenCV asserts (cv::Exception) when a key is looked up in a top level that
// is not a map (found by fuzz_settings).
TEST(YamlReader, TopLevelThatIsNotKeysIsAnError) {
  test::TempDir dir;
  const auto file = dir.write("list.yaml", "%YAML:1.0\n- 1\n- 2\n");
  try {
    YamlReader yaml(file);
    yaml.optional_string("camera_model");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("list.yaml:2: the top level is a sequence"),
              std::string::npos)
        << e.what();
  }
  // A file with no keys at all is still read (every key is then missing).
  EXPECT_FALSE(YamlReader(dir.write("empty.yaml", "%YAML:1.0\n")).has("camera_model"));
}

// OpenCV 4.6's parser loops for minutes on these files (found by
// fuzz_euroc_sensor and fuzz_settings; tests/fuzz/known_hangs/): YamlReader
// refuses a top-level sequence before the parser sees it. A regression shows
// as this test hanging until ctest's timeout.
TEST(YamlReader, FileThatHangsOpenCvsFileParserIsAnError) {
  test::TempDir dir;
  const auto file = dir.write("sensor.yaml", "%YAML:1.\n-----0\ni---\n");
  try {
    YamlReader yaml(file);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sensor.yaml:2: the top level is a sequence"), std::string::npos) << e.what();
  }
  // OpenCV's parser loops on these even from memory (fuzz_settings and
  // fuzz_euroc_sensor, minimized): refused before it runs, naming the line.
  const std::pair<const char*, const char*> loops[] = {{"%YAML:1.0\n----t\n-\n-", "loop.yaml:2: "},
                                                       {"%YAML:1.0\n L:.\n-0\n-", "loop.yaml:2: "},
                                                       {"%YAML:1.0\n a: l\n14e-\n\n", "loop.yaml:2: "}};
  for (const auto& [text, where] : loops) {
    try {
      YamlReader yaml(dir.write("loop.yaml", text));
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  }
  // A document marker is not a sequence.
  EXPECT_EQ(YamlReader(dir.write("marker.yaml", "%YAML:1.0\n---\nCamera.fps: 30\n")).optional_number("Camera.fps"), 30.0);
}

// OpenCV's parser threw std::length_error on this damaged file (found by
// fuzz_settings, kept in its corpus); it is an Error naming the file.
TEST(YamlReader, ParserFailureOtherThanCvExceptionIsAnError) {
  const std::filesystem::path file =
      std::filesystem::path(STILLSLAM_SOURCE_DIR) / "tests/fuzz/corpus/settings/finding_parser_length_error.yaml";
  try {
    YamlReader yaml(file);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("finding_parser_length_error.yaml: not a valid OpenCV YAML file"),
              std::string::npos)
        << e.what();
  }
}

TEST(YamlReader, RowCommaRepairOnALongRunOfBlanks) {
  test::TempDir dir;
  // Rows of one number each, the first break after 100000 blanks: every
  // break gets its comma.
  const auto file = dir.write("rows.yaml", "%YAML:1.0\nm: !!opencv-matrix\n  rows: 2\n  cols: 2\n  dt: d\n  data: [1.5" +
                                               std::string(100000, ' ') + "\n    -2.0\n    3.0\n    4.25]\n");
  const auto m = YamlReader(file).optional_matrix("m");
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ((*m)(0, 0), 1.5);
  EXPECT_EQ((*m)(0, 1), -2.0);
  EXPECT_EQ((*m)(1, 0), 3.0);
  EXPECT_EQ((*m)(1, 1), 4.25);
}

}  // namespace
}  // namespace stillslam
