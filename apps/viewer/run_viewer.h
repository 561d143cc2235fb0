#pragma once
// `--viewer [PORT] --viewer-host HOST` of `stillslam run` and `stillslam ros2`:
// starts the HTTP viewer before the run and hooks it into the run loop
// (publisher, pause gate).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/settings/settings.h"
#include "stillslam/system/dataset_runner.h"
#include "stillslam/system/pause_gate.h"
#include "viewer/viewer_server.h"

namespace stillslam::apps {

struct RunViewerArgs {
  CLI::Option* viewer = nullptr;  // given: serve the viewer
  // The PORT given, as text: CLI11 hands an int option given without a value
  // over as 0, which is a port here. Empty: Viewer.port.
  std::vector<std::string> port;
  std::string host;               // empty: Viewer.host
};
void add_viewer_options(CLI::App& cmd, RunViewerArgs& args);

// The server and the pause gate it drives, alive for the whole run.
struct RunViewer {
  PauseGate pause;
  std::unique_ptr<viewer::ViewerServer> server;
};

// Null without --viewer. Otherwise listens (or throws stillslam::Error),
// prints the address on stderr and sets options' pause gate and hooks.
// `groundtruth` (optional): drawn in the active map; unreadable: a warning.
std::unique_ptr<RunViewer> start_run_viewer(const RunViewerArgs& args, const Settings& settings, RunOptions& options,
                                            const std::optional<std::filesystem::path>& groundtruth);

}  // namespace stillslam::apps
