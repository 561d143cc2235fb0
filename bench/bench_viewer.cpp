// The live viewer's cost per frame: the same dataset run without a viewer and
// with one (ViewerServer, as `stillslam run --viewer` starts it) that has a
// page connected the whole time (a headless client reading the event stream,
// as a browser does: every frame JPEG, overlay and map update it is sent).
// The variants alternate (A B A B ...) so drift in the machine's load hits
// both alike. Per-frame time = frame building + tracking + publishing (the
// snapshot the viewer reads), on the tracking thread.
//
//   build/bench/bench_viewer --config S.yaml --input DIR [--repeats 2] [--max-frames N]
//       [--no-segmentation] [--deterministic] [--json OUT]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "stillslam/core/error.h"
#include "stillslam/system/dataset_runner.h"
#include "viewer/viewer_server.h"
// After Eigen: a macro of httplib's dependencies breaks Eigen's templates when seen first.
#include <httplib.h>

using namespace stillslam;

namespace {

struct Args {
  std::string config, input, json;
  int repeats = 2;
  std::size_t max_frames = 0;
  bool no_segmentation = false, deterministic = false;
};

struct Variant {
  std::vector<double> frame_ms;  // all repeats
  double wall_seconds = 0;
  std::size_t bytes_received = 0;
  std::vector<double> encode_ms;  // the feed's mean per update, per run
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

void run_once(const Args& a, const Settings& settings, const Dataset& dataset, bool viewer, Variant& out) {
  RunOptions options;
  options.system.use_segmentation = !a.no_segmentation;
  options.system.deterministic = a.deterministic;
  options.system.vocabulary_path = resolve_vocabulary_option("");
  if (a.max_frames > 0) options.max_frames = a.max_frames;
  std::unique_ptr<viewer::ViewerServer> server;
  std::unique_ptr<httplib::Client> client;
  std::thread page;
  std::atomic<bool> done{false};
  PauseGate pause;
  if (viewer) {
    ViewerOptions viewer_options = settings.viewer;
    viewer_options.port = 0;
    server = std::make_unique<viewer::ViewerServer>(viewer_options, &pause);
    options.pause = &pause;
    options.on_start = [&](const System& system) { server->attach(&system.publisher()); };
    options.on_end = [&] { server->attach(nullptr); };
    client = std::make_unique<httplib::Client>("127.0.0.1", server->port());
    page = std::thread([&] {
      client->Get("/api/events", [&](const char*, std::size_t size) {
        out.bytes_received += size;
        return !done.load();
      });
    });
  }
  const RunResult result = run_dataset(settings, dataset, options);
  done = true;
  if (page.joinable()) page.join();
  if (client) {
    if (auto state = client->Get("/api/state")) {
      out.encode_ms.push_back(nlohmann::json::parse(state->body).value("viewer_encode_ms", 0.0));
    }
  }
  for (const FrameStats& f : result.frames) out.frame_ms.push_back(f.total_ms + f.publish_ms);
  out.wall_seconds += result.wall_seconds;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app("Viewer cost per frame (see the comment at the top of bench/bench_viewer.cpp)", "bench_viewer");
  app.add_option("--config", a.config, "settings YAML")->required();
  app.add_option("--input", a.input, "dataset folder")->required();
  app.add_option("--repeats", a.repeats, "runs of each variant, alternating")->check(CLI::Range(1, 20));
  app.add_option("--max-frames", a.max_frames, "process at most N frames");
  app.add_flag("--no-segmentation", a.no_segmentation, "without dynamic masks");
  app.add_flag("--deterministic", a.deterministic, "synchronous local mapping");
  app.add_option("--json", a.json, "write the results as JSON here");
  CLI11_PARSE(app, argc, argv);
  try {
    const Settings settings = load_settings(a.config);
    const auto dataset = open_dataset(a.input, settings);
    Variant without, with;
    for (int r = 0; r < a.repeats; ++r) {
      run_once(a, settings, *dataset, false, without);
      run_once(a, settings, *dataset, true, with);
    }
    const double ratio = median(with.frame_ms) / median(without.frame_ms);
    nlohmann::json j = {
        {"frames_per_run", without.frame_ms.size() / static_cast<std::size_t>(a.repeats)},
        {"repeats", a.repeats},
        {"without_viewer", {{"median_ms", median(without.frame_ms)}, {"mean_ms", mean(without.frame_ms)},
                            {"wall_seconds", without.wall_seconds}}},
        {"with_viewer", {{"median_ms", median(with.frame_ms)}, {"mean_ms", mean(with.frame_ms)},
                         {"wall_seconds", with.wall_seconds}, {"bytes_streamed", with.bytes_received},
                         {"viewer_encode_ms_per_update", mean(with.encode_ms)}}},
        {"median_ratio", ratio}};
    std::cout << "per frame [ms]  without viewer: median " << median(without.frame_ms) << ", mean "
              << mean(without.frame_ms) << "  with a connected page: median " << median(with.frame_ms) << ", mean "
              << mean(with.frame_ms) << "  ratio of medians " << ratio << "  (" << with.bytes_received / 1e6
              << " MB streamed; the viewer thread's encoding: " << mean(with.encode_ms) << " ms per update)\n";
    if (!a.json.empty()) std::ofstream(a.json) << j.dump(2) << "\n";
  } catch (const Error& e) {
    std::cerr << "bench_viewer: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
