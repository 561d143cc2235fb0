#include "viewer/run_viewer.h"

#include <spdlog/spdlog.h>

#include <iostream>
#include <stdexcept>

#include "stillslam/core/error.h"
#include "stillslam/io/trajectory.h"

namespace stillslam::apps {

void add_viewer_options(CLI::App& cmd, RunViewerArgs& args) {
  args.viewer = cmd.add_option("--viewer", args.port,
                               "serve a live web viewer while the run lasts, on 127.0.0.1:PORT (default: Viewer.port, "
                               "8080; 0: any free port); its address is printed on stderr")
                    ->expected(0, 1);
  cmd.add_option("--viewer-host", args.host,
                 "address the viewer listens on (default: Viewer.host, 127.0.0.1, this machine only); another "
                 "address lets anyone who reaches it watch and pause the run")
      ->needs(args.viewer);
}

std::unique_ptr<RunViewer> start_run_viewer(const RunViewerArgs& args, const Settings& settings, RunOptions& options,
                                            const std::optional<std::filesystem::path>& groundtruth) {
  if (args.viewer == nullptr || args.viewer->count() == 0) return nullptr;
  ViewerOptions viewer_options = settings.viewer;
  if (!args.port.empty() && !args.port.front().empty()) {
    const std::string& text = args.port.front();
    std::size_t used = 0;
    try {
      viewer_options.port = std::stoi(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size()) {
      throw Error("--viewer " + text + ": the port must be a number in [0, 65535] (0: any free port)");
    }
  }
  if (!args.host.empty()) viewer_options.host = args.host;
  try {
    viewer_options.check();
  } catch (const Error& e) {
    throw Error(std::string("--viewer / --viewer-host: ") + e.what());
  }
  if (!viewer::is_loopback_host(viewer_options.host)) {
    spdlog::warn("viewer: listening on {}, not only on this machine: anyone who reaches it can watch the camera "
                 "and pause the run (no authentication)", viewer_options.host);
  }
  auto out = std::make_unique<RunViewer>();
  out->server = std::make_unique<viewer::ViewerServer>(viewer_options, &out->pause);
  if (groundtruth) {
    try {
      out->server->set_groundtruth(read_trajectory(*groundtruth));
    } catch (const Error& e) {
      spdlog::warn("viewer: no ground truth drawn: {}", e.what());
    }
  }
  std::cerr << "viewer: " << out->server->url() << std::endl;
  viewer::ViewerServer* server = out->server.get();
  options.pause = &out->pause;
  options.on_start = [server](const System& system) { server->attach(&system.publisher()); };
  options.on_end = [server] { server->attach(nullptr); };
  return out;
}

}  // namespace stillslam::apps
