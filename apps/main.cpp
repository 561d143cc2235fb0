#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>

#include "commands.h"
#include "stillslam/core/error.h"

int main(int argc, char** argv) {
  // Log lines (info, warnings, errors) go to stderr; stdout carries only the
  // results the commands print, so `stillslam eval ... > results.txt` holds no log.
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("", std::make_shared<spdlog::sinks::stderr_color_sink_mt>()));
  CLI::App app{"stillslam: feature-based visual SLAM that ignores moving people and objects"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "stillslam 0.1");
  stillslam::apps::add_run_command(app);
  stillslam::apps::add_eval_command(app);
  stillslam::apps::add_report_command(app);
  stillslam::apps::add_simulate_command(app);
  stillslam::apps::add_segment_command(app);
  stillslam::apps::add_bench_command(app);
  stillslam::apps::add_vocab_command(app);
  stillslam::apps::add_bag_info_command(app);
  stillslam::apps::add_bag_export_command(app);
  stillslam::apps::add_bag_write_command(app);
  stillslam::apps::add_ros2_command(app);
  stillslam::apps::add_ros2_replay_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A usage error exits 1 like every other error (CLI11's own codes are
    // 1xx); a command's own code (CLI::RuntimeError: `run`'s 128+signal) is kept.
    const int code = app.exit(e);
    return code == 0 || e.get_name() == "RuntimeError" ? code : 1;
  } catch (const stillslam::Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("unexpected error: {}", e.what());
    return 2;
  }
  return 0;
}
