// JSON keys and values, the terminal table, the SVG plots, and the
// `stillslam eval` command end to end (when the binary has been built).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <unistd.h>

#include "stillslam/eval/evaluate.h"
#include "stillslam/eval/evaluation_plots.h"
#include "stillslam/eval/evaluation_report.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("stillslam_test_eval_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A small planar loop with a known 2 cm offset on every estimated position.
std::pair<Trajectory, Trajectory> offset_loop() {
  Trajectory gt(120), est(120);
  for (std::size_t i = 0; i < gt.size(); ++i) {
    const double a = 2 * M_PI * static_cast<double>(i) / 120.0;
    gt[i].timestamp = est[i].timestamp = 10.0 + 0.1 * static_cast<double>(i);
    gt[i].T_world_cam.translation() = Eigen::Vector3d(3 * std::cos(a), 2 * std::sin(a), 0.1 * std::sin(3 * a));
    est[i].T_world_cam.translation() = gt[i].T_world_cam.translation() + Eigen::Vector3d(0, 0, 0.02);
  }
  return {gt, est};
}

TEST(EvaluationReport, JsonHasTheStableKeys) {
  const auto [gt, est] = offset_loop();
  EvaluationOptions options;
  options.alignment = AlignmentType::None;
  const EvaluationResult r = evaluate(gt, est, options);
  const nlohmann::json j = evaluation_to_json(r, options);
  EXPECT_EQ(j.at("pairs").get<int>(), 120);
  for (const char* key : {"ape", "rpe_trans", "rpe_rot"}) {
    for (const char* stat : {"rmse", "mean", "median", "std", "min", "max"}) {
      EXPECT_TRUE(j.at(key).contains(stat)) << key << "." << stat;
    }
  }
  EXPECT_NEAR(j.at("ape").at("rmse").get<double>(), 0.02, 1e-12);
  EXPECT_NEAR(j.at("ape").at("std").get<double>(), 0.0, 1e-12);
  EXPECT_EQ(j.at("alignment").at("type").get<std::string>(), "none");
  EXPECT_EQ(j.at("alignment").at("rotation").size(), 3u);
  EXPECT_EQ(j.at("association").at("method").get<std::string>(), "tum");
  EXPECT_EQ(j.at("rpe").at("pairs").get<int>(), 119);

  const std::string table = format_evaluation_table(r, options);
  EXPECT_NE(table.find("ape [m]"), std::string::npos) << table;
  EXPECT_NE(table.find("0.020000"), std::string::npos) << table;
}

TEST(EvaluationPlots, WritesTwoSvgsWithEveryPoseInsideTheCanvas) {
  const auto [gt, est] = offset_loop();
  const EvaluationResult r = evaluate(gt, est, EvaluationOptions{});
  const fs::path plot = temp_dir() / "plot.svg";
  const fs::path error_plot = write_evaluation_plots(plot, r);
  EXPECT_EQ(error_plot, temp_dir() / "plot_error.svg");
  for (const fs::path& path : {plot, error_plot}) {
    const std::string svg = read_text(path);
    ASSERT_EQ(svg.rfind("<svg", 0), 0u) << path;
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    const std::regex points_attr("points=\"([^\"]*)\"");
    int polylines = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), points_attr); it != std::sregex_iterator(); ++it) {
      ++polylines;
      std::istringstream points((*it)[1].str());
      std::string point;
      while (points >> point) {
        const double x = std::stod(point.substr(0, point.find(',')));
        const double y = std::stod(point.substr(point.find(',') + 1));
        EXPECT_GE(x, 0.0);
        EXPECT_LE(x, 800.0);
        EXPECT_GE(y, 0.0);
        EXPECT_LE(y, 600.0);
      }
    }
    EXPECT_EQ(polylines, 2) << path;
  }
  // The trajectory view uses x-y (the loop is flat in z) and has one point per pose.
  const std::string view = read_text(plot);
  EXPECT_NE(view.find("x [m]"), std::string::npos);
  EXPECT_NE(view.find("y [m]"), std::string::npos);
}

TEST(EvaluationPlots, TrackingGapsBreakTheLines) {
  auto [gt, est] = offset_loop();
  // Drop 3 s of poses (30 of them): the views must not bridge the hole.
  gt.erase(gt.begin() + 40, gt.begin() + 70);
  est.erase(est.begin() + 40, est.begin() + 70);
  const EvaluationResult r = evaluate(gt, est, EvaluationOptions{});
  auto count = [](const std::string& svg, const std::string& what) {
    std::size_t n = 0;
    for (auto pos = svg.find(what); pos != std::string::npos; pos = svg.find(what, pos + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count(trajectory_view_svg(r), "<polyline"), 4u);  // two series, two runs each
  EXPECT_EQ(count(ape_over_time_svg(r), "<polyline"), 3u);    // APE in two runs + the rmse line
}

TEST(EvalCommand, WritesJsonEndToEnd) {
  const fs::path binary = STILLSLAM_BINARY;
  if (!fs::exists(binary)) GTEST_SKIP() << binary << " is not built; build the stillslam target first";
  const fs::path shared = fs::path(STILLSLAM_SHARED_DIR) / "data" / "trajectories";
  if (!fs::exists(shared)) GTEST_SKIP() << "shared data not found at " << shared;
  const fs::path json_path = temp_dir() / "fr1.json";
  const std::string command = binary.string() + " eval --gt " + (shared / "freiburg1_xyz-groundtruth.txt").string() +
                              " --est " + (shared / "freiburg1_xyz-rgbdslam.txt").string() + " --json " +
                              json_path.string() + " --plot " + (temp_dir() / "fr1.svg").string() + " > " +
                              (temp_dir() / "stdout.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(temp_dir() / "stdout.txt");
  const nlohmann::json j = nlohmann::json::parse(read_text(json_path));
  EXPECT_EQ(j.at("pairs").get<int>(), 786);
  EXPECT_NEAR(j.at("ape").at("rmse").get<double>(), 0.013473, 1e-6);
  EXPECT_EQ(j.at("inputs").at("gt_format").get<std::string>(), "tum");
  EXPECT_TRUE(fs::exists(temp_dir() / "fr1_error.svg"));
  EXPECT_NE(read_text(temp_dir() / "stdout.txt").find("rpe_rot [deg]"), std::string::npos);

  // A malformed estimate exits non-zero with the file and line in the message.
  const fs::path broken = temp_dir() / "broken.txt";
  std::ofstream(broken) << "1305031102.16 1 2 3 0 0 0 1\n1305031102.19 1 2 x 0 0 0 1\n";
  const std::string bad = binary.string() + " eval --gt " + (shared / "freiburg1_xyz-groundtruth.txt").string() +
                          " --est " + broken.string() + " > " + (temp_dir() / "bad.txt").string() + " 2>&1";
  EXPECT_NE(std::system(bad.c_str()), 0);
  const std::string message = read_text(temp_dir() / "bad.txt");
  EXPECT_NE(message.find("broken.txt, line 2"), std::string::npos) << message;
}

}  // namespace
}  // namespace stillslam
