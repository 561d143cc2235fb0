// `stillslam run --viewer 0` on a small simulated sequence with people (the
// shipped YOLO model masks them): the page, loaded in Debian's headless
// Chromium (through chromedriver) while the run is paused, shows the counts
// the system reported (/api/state, then stats.json once the run is resumed
// and ends). A screenshot is kept in <build>/artifacts/viewer_page.png.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "stillslam/sim/sequence_writer.h"
// After Eigen: a macro of httplib's dependencies breaks Eigen's templates when seen first.
#include "viewer/webdriver_session.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// stillslam run as a child whose merged output is read while it runs; a
// child still running when the test ends (a failed assertion while it is
// paused) is killed, not waited for.
class RunningCommand {
 public:
  explicit RunningCommand(const std::string& command) {
    int fds[2] = {-1, -1};
    if (::pipe2(fds, O_CLOEXEC) != 0) return;
    const std::string shell = "exec " + command + " 2>&1";
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(fds[1], 1);
      ::execl("/bin/sh", "sh", "-c", shell.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    reader_ = std::thread([this, fd = fds[0]] {
      char buffer[4096];
      for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof(buffer));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        std::lock_guard lock(mutex_);
        output_.append(buffer, static_cast<std::size_t>(n));
      }
      ::close(fd);
    });
  }
  ~RunningCommand() {
    if (pid_ > 0 && !waited_) ::kill(pid_, SIGKILL);
    finish();
  }
  int finish() {
    if (pid_ > 0 && !waited_) {
      while (::waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
      }
      waited_ = true;
    }
    if (reader_.joinable()) reader_.join();
    return status_;
  }
  std::string output() const {
    std::lock_guard lock(mutex_);
    return output_;
  }

 private:
  pid_t pid_ = -1;
  bool waited_ = false;
  int status_ = -1;
  std::thread reader_;
  mutable std::mutex mutex_;
  std::string output_;
};

nlohmann::json get_json(httplib::Client& client, const std::string& path) {
  auto res = client.Get(path);
  return res && res->status == 200 ? nlohmann::json::parse(res->body) : nlohmann::json::object();
}

TEST(ViewerPage, ChromiumShowsTheCountsTheSystemReported) {
  if (!fs::exists(STILLSLAM_BINARY)) GTEST_SKIP() << "build the stillslam binary first (" << STILLSLAM_BINARY << ")";
  const fs::path dir = fs::temp_directory_path() / "stillslam_test_viewer_page";
  fs::remove_all(dir);
  sim::SimulationOptions sim;
  sim.trajectory = "walking_xyz";
  sim.frames = 24;
  sim.width = 400;
  sim.height = 300;
  sim.supersampling = 1;
  sim.data_dir = fs::path(STILLSLAM_SOURCE_DIR) / "data";
  const sim::SequenceSummary seq = sim::write_sequence(dir / "seq", sim);

  RunningCommand run(std::string(STILLSLAM_BINARY) + " run --config " + seq.settings.string() + " --input " +
                     (dir / "seq").string() + " --output " + (dir / "out").string() +
                     " --deterministic --vocabulary none --viewer 0");
  // --viewer 0: the port it got is printed on stderr.
  int port = 0;
  const std::regex address(R"(viewer: http://127\.0\.0\.1:(\d+)/)");
  for (int i = 0; i < 600 && port == 0; ++i) {
    std::smatch m;
    const std::string out = run.output();
    if (std::regex_search(out, m, address)) port = std::stoi(m[1].str());
    else std::this_thread::sleep_for(50ms);
  }
  ASSERT_GT(port, 0) << run.output();
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(10, 0);

  // Paused at once (the model is still loading), then stepped 12 frames: the
  // same frame is held however fast the machine is.
  ASSERT_TRUE(client.Post("/api/pause")) << run.output();
  const auto settled = [&client] {
    nlohmann::json now = get_json(client, "/api/state");
    for (int i = 0; i < 100; ++i) {
      std::this_thread::sleep_for(200ms);
      const nlohmann::json later = get_json(client, "/api/state");
      const auto same = [&](const char* key) { return later.value(key, -1) == now.value(key, -1); };
      if (same("frame") && same("map_points") && same("keyframes")) break;
      now = later;
    }
    return now;
  };
  const int done_before = settled().value("frame", -1) + 1;
  constexpr int kSteps = 12;
  for (int i = 0; i < kSteps; ++i) ASSERT_TRUE(client.Post("/api/step"));
  nlohmann::json state = nlohmann::json::object();
  for (int i = 0; i < 2400 && state.value("frame", -1) != done_before + kSteps - 1; ++i) {
    std::this_thread::sleep_for(25ms);
    state = get_json(client, "/api/state");
  }
  state = settled();
  ASSERT_EQ(state.value("frame", -1), done_before + kSteps - 1) << state.dump() << run.output();
  ASSERT_TRUE(state["paused"].get<bool>()) << state.dump();
  EXPECT_GT(state["features_removed"].get<int>(), 0) << "no feature removed: the model saw no person? " << state;
  EXPECT_GT(state["map_points"].get<int>(), 0);

  if (!fs::exists(test::kChromium) || !fs::exists(test::kChromedriver)) {
    client.Post("/api/resume");
    run.finish();
    GTEST_SKIP() << test::kChromium << " or " << test::kChromedriver
                 << " is absent (apt-get install chromium chromium-driver): the page was not loaded";
  }
  {
    test::WebDriverSession browser(dir / "chromium");
    ASSERT_TRUE(browser.ok()) << "chromedriver / chromium did not start: " << browser.error();
    ASSERT_TRUE(browser.open("http://127.0.0.1:" + std::to_string(port) + "/"));
    // What the page shows, once the held frame is drawn (image loaded, overlay on it).
    const std::string read_page =
        "const t = (id) => document.getElementById(id) ? document.getElementById(id).textContent : null;"
        "return {frame: t('c-frame'), map_points: t('c-map_points'), keyframes: t('c-keyframes'),"
        " removed: t('c-features_removed'), kept: t('c-features_kept'), status: t('run-status'),"
        " drawn: document.getElementById('frame-canvas').dataset.frame || '',"
        " webgl: document.querySelector('#map-view canvas') !== null,"
        " maps: document.querySelectorAll('#map-list input').length,"
        " groundtruth: !document.getElementById('gt-key').hidden,"
        " elements: ['frame-canvas', 'map-view', 'counters', 'btn-pause', 'btn-step', 'btn-resume']"
        "   .filter((id) => document.getElementById(id) !== null).length};";
    const std::string frame = std::to_string(state["frame"].get<int>());
    nlohmann::json page;
    for (int i = 0; i < 200; ++i) {
      page = browser.run(read_page);
      if (page.is_object() && page["drawn"] == frame && page["frame"] == frame && page["maps"].get<int>() > 0) break;
      std::this_thread::sleep_for(50ms);
    }
    ASSERT_TRUE(page.is_object()) << page;
    EXPECT_EQ(page["elements"], 6) << page;
    EXPECT_EQ(page["frame"], frame) << page;
    EXPECT_EQ(page["drawn"], frame) << page;
    EXPECT_EQ(page["map_points"], std::to_string(state["map_points"].get<int>())) << page;
    EXPECT_EQ(page["keyframes"], std::to_string(state["keyframes"].get<int>())) << page;
    EXPECT_EQ(page["removed"], std::to_string(state["features_removed"].get<int>())) << page;
    EXPECT_EQ(page["kept"], std::to_string(state["features_kept"].get<int>())) << page;
    EXPECT_EQ(page["status"], "paused") << page;
    EXPECT_TRUE(page["webgl"].get<bool>()) << "no WebGL canvas (swiftshader): " << page;
    EXPECT_EQ(page["maps"], 1) << page;
    EXPECT_TRUE(page["groundtruth"].get<bool>()) << "the sequence's groundtruth.txt is not drawn: " << page;

    const fs::path artifacts(STILLSLAM_ARTIFACT_DIR);
    fs::create_directories(artifacts);
    const fs::path shot = artifacts / "viewer_page.png";
    const std::string png = browser.screenshot_png();
    std::ofstream(shot, std::ios::binary) << png;
    const cv::Mat image = cv::imread(shot.string());
    EXPECT_EQ(image.cols, 1500) << shot;
  }

  ASSERT_TRUE(client.Post("/api/resume"));
  const int status = run.finish();
  ASSERT_EQ(status, 0) << run.output();
  // What the page showed for that frame is what stats.json says about it.
  std::ifstream stats_file(dir / "out" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  const auto frame = std::find_if(stats["frames"].begin(), stats["frames"].end(),
                                  [&](const nlohmann::json& f) { return f["index"] == state["frame"]; });
  ASSERT_NE(frame, stats["frames"].end());
  EXPECT_EQ((*frame)["features_after_filter"], state["features_kept"]);
  EXPECT_EQ((*frame)["detections"], state["detections"]);
  EXPECT_EQ((*frame)["state"], state["state"]);

  // A PORT that is not a number is refused, naming it.
  RunningCommand bad(std::string(STILLSLAM_BINARY) + " run --config " + seq.settings.string() + " --input " +
                     (dir / "seq").string() + " --output " + (dir / "out_bad").string() +
                     " --no-segmentation --vocabulary none --viewer 80a");
  EXPECT_NE(bad.finish(), 0);
  EXPECT_NE(bad.output().find("--viewer 80a: the port must be a number in [0, 65535]"), std::string::npos)
      << bad.output();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stillslam
