#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the
// top-level CLI11 app; main.cpp calls these in the order shown by --help.
#include <CLI/CLI.hpp>

namespace stillslam::apps {

void add_eval_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_segment_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_vocab_command(CLI::App& app);
void add_bag_info_command(CLI::App& app);
void add_bag_export_command(CLI::App& app);
void add_bag_write_command(CLI::App& app);
// apps/ros2/ (the stillslam_ros2 target)
void add_ros2_command(CLI::App& app);
void add_ros2_replay_command(CLI::App& app);

}  // namespace stillslam::apps
