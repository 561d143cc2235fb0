// `stillslam report` and `stillslam run --save-frames` end to end through the
// binary: a small simulated run with people (segmentation on, frames saved)
// and one without segmentation; the report's numbers against `stillslam
// eval` and stats.json, the page rendered offline in headless Chromium, and
// the saved frames' count, size and colours.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/run_stillslam.h"
#include "common/small_sequence.h"
#include "stillslam/benchmark/html_text.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;
using test::run_stillslam;

constexpr int kFrames = 12;

std::string read_file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

// The text of the element with id `id` (up to the next '<'); empty when absent.
// (No std::regex: libstdc++'s recursion overflows the stack on the long data URIs.)
std::string element_text(const std::string& html, const std::string& id) {
  const std::size_t at = html.find("id=\"" + id + "\"");
  if (at == std::string::npos) return {};
  const std::size_t open = html.find('>', at);
  const std::size_t close = html.find('<', open);
  if (open == std::string::npos || close == std::string::npos) return {};
  return html.substr(open + 1, close - open - 1);
}

std::size_t count_files(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file() ? 1 : 0;
  return n;
}

// Pixels exactly of colour `bgr`.
int count_color(const cv::Mat& image, const cv::Vec3b& bgr) {
  int n = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) n += image.at<cv::Vec3b>(y, x) == bgr ? 1 : 0;
  }
  return n;
}

// Two runs of one sequence, made once for all tests of this file.
struct Runs {
  fs::path dir, seq, on, off, frames, frames_every;
  std::string on_log, off_log;
  bool ok = false;
};

class RunReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!fs::exists(STILLSLAM_BINARY)) return;
    runs_ = std::make_unique<Runs>();
    Runs& r = *runs_;
    r.dir = fs::temp_directory_path() / ("stillslam_test_run_report_" + std::to_string(::getpid()));
    fs::remove_all(r.dir);
    const sim::SequenceSummary seq = test::write_small_sequence(r.dir, kFrames, true);
    r.seq = r.dir / "seq";
    r.on = r.dir / "on";
    r.off = r.dir / "off";
    r.frames = r.dir / "frames";
    r.frames_every = r.dir / "frames_every";
    const std::string common = "run --config " + seq.settings.string() + " --input " + r.seq.string() +
                               " --deterministic --vocabulary none";
    const test::CommandRun on = run_stillslam(
        common + " --output " + r.on.string() + " --save-frames " + r.frames.string(), true);
    const test::CommandRun off = run_stillslam(common + " --no-segmentation --output " + r.off.string() +
                                                   " --save-frames " + r.frames_every.string() +
                                                   " --save-frames-every 5",
                                               true);
    r.on_log = on.out;
    r.off_log = off.out;
    r.ok = on.status == 0 && off.status == 0;
  }
  static void TearDownTestSuite() {
    if (runs_) fs::remove_all(runs_->dir);
    runs_.reset();
  }
  void SetUp() override {
    if (!runs_) GTEST_SKIP() << STILLSLAM_BINARY << " is not built (build the stillslam target first)";
    ASSERT_TRUE(runs_->ok) << "segmentation on:\n" << runs_->on_log << "\nsegmentation off:\n" << runs_->off_log;
  }
  // Writes the report of the two runs; returns its path.
  static fs::path write_report(const std::string& extra = "") {
    const fs::path html = runs_->dir / "report.html";
    const test::CommandRun r = run_stillslam("report " + runs_->on.string() + " --compare " + runs_->off.string() +
                                                 " --out " + html.string() + " " + extra,
                                             true);
    EXPECT_EQ(r.status, 0) << r.out;
    return html;
  }
  static double eval_ate(const fs::path& run, std::size_t* pairs) {
    const fs::path json = runs_->dir / "eval.json";
    const test::CommandRun r = run_stillslam("eval --gt " + (runs_->seq / "groundtruth.txt").string() + " --est " +
                                                 (run / "trajectory.txt").string() + " --json " + json.string(),
                                             true);
    EXPECT_EQ(r.status, 0) << r.out;
    const nlohmann::json j = read_json(json);
    *pairs = j["pairs"].get<std::size_t>();
    return j["ape"]["rmse"].get<double>();
  }

  static std::unique_ptr<Runs> runs_;
};

std::unique_ptr<Runs> RunReport::runs_;

TEST_F(RunReport, HoldsTheAteAndFrameCountsOfEachRun) {
  const std::string html = read_file_text(write_report());
  for (int k = 0; k < 2; ++k) {
    const fs::path run = k == 0 ? runs_->on : runs_->off;
    const std::string n = std::to_string(k);
    std::size_t pairs = 0;
    const double ate = eval_ate(run, &pairs);
    const nlohmann::json stats = read_json(run / "stats.json");
    ASSERT_FALSE(element_text(html, "ate-rmse-" + n).empty()) << "no ate-rmse-" << n;
    EXPECT_NEAR(std::stod(element_text(html, "ate-rmse-" + n)), ate, 5e-7) << n;
    EXPECT_NEAR(stats["summary"]["ate_rmse"].get<double>(), ate, 1e-6) << n;  // trajectory.txt is rounded text
    EXPECT_EQ(element_text(html, "ate-pairs-" + n), std::to_string(pairs));
    EXPECT_EQ(element_text(html, "frames-" + n), std::to_string(kFrames));
    EXPECT_EQ(element_text(html, "frames-" + n), std::to_string(stats["frames"].size()));
    EXPECT_EQ(element_text(html, "frames-in-input-" + n), std::to_string(stats["end"]["frames_in_input"].get<int>()));
    EXPECT_EQ(element_text(html, "tracked-" + n), std::to_string(stats["summary"]["tracked"].get<int>()));
    EXPECT_EQ(element_text(html, "lost-" + n), std::to_string(stats["summary"]["lost"].get<int>()));
    EXPECT_EQ(element_text(html, "keyframes-" + n), std::to_string(stats["summary"]["keyframes_in_map"].get<int>()));
  }
  // The people cost the run without masks accuracy, as in the bench test.
  EXPECT_LT(std::stod(element_text(html, "ate-rmse-0")), std::stod(element_text(html, "ate-rmse-1")));
  // Self-contained: every image inline, no script or style from outside.
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  int images = 0;
  for (std::size_t at = html.find("<img"); at != std::string::npos; at = html.find("<img", at + 1)) {
    const std::size_t src = html.find(" src=\"", at);
    ASSERT_NE(src, std::string::npos);
    EXPECT_EQ(html.compare(src + 6, 5, "data:"), 0) << html.substr(src, 40);
    ++images;
  }
  EXPECT_EQ(images, 8 + 3);  // the default 8 of the first run's 12 saved frames, and all 3 of the second
  for (const char* needle : {"<svg", "id=\"view3d\"", "Settings file", "Segmentation.model", "Tracking state"}) {
    EXPECT_NE(html.find(needle), std::string::npos) << needle;
  }
}

TEST_F(RunReport, RendersOfflineInHeadlessChromium) {
  const fs::path chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium)) GTEST_SKIP() << "no " << chromium << " (apt-get install chromium; scripts/setup lists it)";
  const fs::path html = write_report();
  const std::string expected_ate = element_text(read_file_text(html), "ate-rmse-0");
  // No network: every proxy connection fails and no host name resolves.
  const fs::path profile = runs_->dir / "chromium_profile";
  const std::string cmd = "timeout 120 " + chromium.string() +
                          " --headless --disable-gpu --no-sandbox --no-first-run --user-data-dir=" + profile.string() +
                          " --proxy-server=127.0.0.1:9 --host-resolver-rules=\"MAP * ~NOTFOUND\" --dump-dom file://" +
                          html.string() + " 2>/dev/null";
  std::string dom;
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) dom.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << "chromium failed: " << cmd;
  ASSERT_FALSE(expected_ate.empty());
  EXPECT_EQ(element_text(dom, "ate-rmse-0"), expected_ate);
  EXPECT_EQ(element_text(dom, "frames-0"), std::to_string(kFrames));
  EXPECT_EQ(element_text(dom, "frames-1"), std::to_string(kFrames));
  // The inline script ran: the 3D view drew ground truth and both runs.
  EXPECT_NE(dom.find("data-drawn=\"3\""), std::string::npos) << "the 3D view's script did not run";
}

TEST_F(RunReport, SavedFramesShowTheRemovedFeatures) {
  ASSERT_EQ(count_files(runs_->frames), static_cast<std::size_t>(kFrames));
  EXPECT_EQ(count_files(runs_->frames_every), 3u);  // frames 0, 5, 10
  const nlohmann::json stats = read_json(runs_->on / "stats.json");
  EXPECT_EQ(stats["saved_frames"]["written"].get<int>(), kFrames);
  EXPECT_EQ(stats["saved_frames"]["skipped"].get<int>(), 0);
  // The frame where the masks removed the most features (the people are in view).
  std::size_t best = 0;
  int most = -1;
  for (std::size_t i = 0; i < stats["frames"].size(); ++i) {
    const int removed = stats["frames"][i]["features_removed"].get<int>();
    if (removed > most) {
      most = removed;
      best = i;
    }
  }
  ASSERT_GT(most, 20) << "the people were not masked";
  std::vector<fs::path> saved, inputs;
  for (const auto& e : fs::directory_iterator(runs_->frames)) saved.push_back(e.path());
  for (const auto& e : fs::directory_iterator(runs_->seq / "rgb")) inputs.push_back(e.path());
  std::sort(saved.begin(), saved.end());
  std::sort(inputs.begin(), inputs.end());
  ASSERT_EQ(inputs.size(), saved.size());
  const cv::Mat annotated = cv::imread(saved[best].string(), cv::IMREAD_COLOR);
  const cv::Mat input = cv::imread(inputs[best].string(), cv::IMREAD_COLOR);
  ASSERT_EQ(annotated.cols, 400);
  ASSERT_EQ(annotated.rows, 300);
  char prefix[32];
  std::snprintf(prefix, sizeof(prefix), "frame_%06zu_", best);
  EXPECT_EQ(saved[best].filename().string().rfind(prefix, 0), 0u) << saved[best];
  // Red crosses (removed features, 7 pixels each at least partly visible) and magenta outlines.
  const int red = count_color(annotated, {0, 0, 255}) - count_color(input, {0, 0, 255});
  const int magenta = count_color(annotated, {255, 0, 255}) - count_color(input, {255, 0, 255});
  EXPECT_GT(red, 2 * most) << most << " removed features";
  EXPECT_GT(magenta, 100);
}

TEST_F(RunReport, MissingOrMalformedStatsIsAnErrorNamingTheFile) {
  const fs::path empty = runs_->dir / "empty_run";
  fs::create_directories(empty);
  const test::CommandRun r =
      run_stillslam("report " + empty.string() + " --out " + (runs_->dir / "x.html").string(), true);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find((empty / "stats.json").string()), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(runs_->dir / "x.html"));
  // Values of the wrong type: the same kind of error (exit 1), not an internal one.
  std::ofstream(empty / "stats.json") << R"({"frames": [{"index": "x", "state": 3}], "end": 5})";
  std::ofstream(empty / "trajectory.txt") << "";
  const test::CommandRun typed =
      run_stillslam("report " + empty.string() + " --out " + (runs_->dir / "x.html").string(), true);
  EXPECT_EQ(WEXITSTATUS(typed.status), 1) << typed.out;
  EXPECT_NE(typed.out.find((empty / "stats.json").string()), std::string::npos) << typed.out;
}

// Frames of an earlier run in the --save-frames folder: refused before the
// run starts, and left alone, so a report never mixes two runs' frames.
TEST_F(RunReport, SaveFramesRefusesAFolderWithEarlierFrames) {
  const test::CommandRun r = run_stillslam("run --config " + (runs_->seq / "settings.yaml").string() + " --input " +
                                               runs_->seq.string() + " --output " + (runs_->dir / "again").string() +
                                               " --no-segmentation --save-frames " + runs_->frames.string(),
                                           true);
  EXPECT_EQ(WEXITSTATUS(r.status), 1) << r.out;
  EXPECT_NE(r.out.find("frames of an earlier run"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--force"), std::string::npos) << r.out;
  EXPECT_EQ(count_files(runs_->frames), static_cast<std::size_t>(kFrames));
}

// A run stopped before its first frame (empty trajectory.txt, no frames): a
// report with zero counts and no ATE, not an error.
TEST_F(RunReport, AnEmptyRunStillGetsAReport) {
  const fs::path empty = runs_->dir / "stopped_run";
  fs::create_directories(empty);
  std::ofstream(empty / "stats.json") << R"({"frames": [], "end": {"frames_in_input": 12}})";
  std::ofstream(empty / "trajectory.txt") << "";
  const fs::path out = runs_->dir / "stopped.html";
  const test::CommandRun r = run_stillslam("report " + empty.string() + " --gt " +
                                               (runs_->seq / "groundtruth.txt").string() + " --out " + out.string(),
                                           true);
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string html = read_file_text(out);
  EXPECT_EQ(element_text(html, "frames-0"), "0");
  EXPECT_EQ(element_text(html, "frames-in-input-0"), "12");
  EXPECT_EQ(element_text(html, "ate-rmse-0").rfind("n/a", 0), 0u) << element_text(html, "ate-rmse-0");
}

TEST(HtmlText, EscapesAndEncodes) {
  EXPECT_EQ(html_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
  EXPECT_EQ(base64_encode({}), "");
  EXPECT_EQ(base64_encode({'f'}), "Zg==");
  EXPECT_EQ(base64_encode({'f', 'o'}), "Zm8=");
  EXPECT_EQ(base64_encode({'f', 'o', 'o', 'b', 'a', 'r'}), "Zm9vYmFy");
  EXPECT_EQ(data_uri("image/png", {0xff}), "data:image/png;base64,/w==");
}

}  // namespace
}  // namespace stillslam
