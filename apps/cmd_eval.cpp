// `stillslam eval`: compare an estimated trajectory with ground truth (ATE/APE
// after alignment, RPE), as TUM's evaluate_ate/rpe and evo do. A thin wrapper
// around eval/evaluate.h.
#include <spdlog/spdlog.h>

#include <iostream>
#include <optional>

#include "commands.h"
#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/eval/evaluate.h"
#include "stillslam/eval/evaluation_plots.h"
#include "stillslam/eval/evaluation_report.h"
#include "stillslam/io/trajectory.h"

namespace stillslam::apps {
namespace {

struct EvalArgs {
  std::string gt, est, format, gt_format, est_format, gt_times, est_times;
  std::string align = "se3";
  std::string association = "tum";
  double max_dt = 0;
  bool max_dt_given = false;  // without --max-dt the association method's default
  double offset = 0;
  double rpe_delta = 1;
  std::string rpe_unit = "frames";
  bool rpe_all_pairs = false;
  std::string duplicate_stamps = "last";
  std::string json, plot;
};

Trajectory load(const std::string& path, const std::string& format, const std::string& times,
                DuplicateStamps duplicates) {
  if (!times.empty()) {
    if (!format.empty() && parse_trajectory_format(format) != TrajectoryFormat::Kitti) {
      throw Error("a times file (" + times + ") only applies to KITTI poses; drop it or use --*-format kitti");
    }
    return read_kitti_trajectory(path, times, duplicates);
  }
  std::optional<TrajectoryFormat> chosen;
  if (!format.empty()) chosen = parse_trajectory_format(format);
  return read_trajectory(path, chosen, duplicates);
}

std::string format_name(const std::string& path, const std::string& format) {
  return format.empty() ? to_string(detect_trajectory_format(path)) : to_string(parse_trajectory_format(format));
}

// Every numeric option is checked before use: a NaN, negative or absurd value
// is an error naming the option and its range, never a silent default.
void check_numbers(const EvalArgs& args) {
  if (args.max_dt_given) option_check::in_half_open("--max-dt", args.max_dt, 0, 10);
  option_check::in_range("--offset", args.offset, -1e10, 1e10);
  option_check::in_half_open("--rpe-delta", args.rpe_delta, 0, 1e9);
}

void run_eval(EvalArgs args) {
  check_numbers(args);
  if (args.gt_format.empty()) args.gt_format = args.format;
  if (args.est_format.empty()) args.est_format = args.format;
  EvaluationOptions options;
  options.alignment = parse_alignment_type(args.align);
  options.association.method = parse_association_method(args.association);
  options.association.max_dt = args.max_dt_given ? args.max_dt : 0;  // 0: the method's default
  options.association.offset = args.offset;
  options.rpe.delta = args.rpe_delta;
  options.rpe.unit = parse_delta_unit(args.rpe_unit);
  options.rpe.all_pairs = args.rpe_all_pairs;

  const DuplicateStamps duplicates =
      args.duplicate_stamps == "last" ? DuplicateStamps::KeepLast : DuplicateStamps::Error;
  const Trajectory gt = load(args.gt, args.gt_format, args.gt_times, duplicates);
  const Trajectory est = load(args.est, args.est_format, args.est_times, duplicates);
  const EvaluationResult result = evaluate(gt, est, options);

  std::cout << format_evaluation_table(result, options);
  if (!args.json.empty()) {
    const nlohmann::json inputs = {{"gt", args.gt},
                                   {"est", args.est},
                                   {"gt_format", format_name(args.gt, args.gt_format)},
                                   {"est_format", format_name(args.est, args.est_format)}};
    write_evaluation_json(args.json, result, options, {{"inputs", inputs}});
  }
  if (!args.plot.empty()) {
    const auto error_plot = write_evaluation_plots(args.plot, result);
    spdlog::info("plots: {} and {}", args.plot, error_plot.string());
  }
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand("eval", "Evaluate a trajectory against ground truth (APE after alignment, RPE)");
  // The readers check the paths (missing, a folder, unreadable) with the file's role in the message.
  cmd->add_option("--gt", args->gt, "Ground-truth trajectory (TUM, KITTI or EuRoC csv; format detected)")->required();
  cmd->add_option("--est", args->est, "Estimated trajectory (TUM, KITTI or EuRoC csv; format detected)")->required();
  const auto formats = CLI::IsMember({"tum", "kitti", "euroc"}, CLI::ignore_case);
  cmd->add_option("--format", args->format,
                  "Format of both files: tum, kitti, euroc (a csv without a header naming the quaternion "
                  "columns needs it)")
      ->check(formats);
  cmd->add_option("--gt-format", args->gt_format, "Format of the ground truth (overrides --format and detection)")
      ->check(formats);
  cmd->add_option("--est-format", args->est_format, "Format of the estimate (overrides --format and detection)")
      ->check(formats);
  cmd->add_option("--gt-times", args->gt_times, "Timestamps for KITTI ground truth (one per line)");
  cmd->add_option("--est-times", args->est_times, "Timestamps for a KITTI estimate (one per line)");
  cmd->add_option("--align", args->align, "se3 (rigid), sim3 (rigid + scale, monocular) or none")
      ->capture_default_str();
  cmd->add_option("--association", args->association,
                  "tum: greedy unique matching as TUM associate.py; nearest: evo's nearest neighbour")
      ->capture_default_str();
  auto* max_dt = cmd->add_option("--max-dt", args->max_dt,
                                  "Largest stamp difference to associate, seconds, in (0, 10] (default 0.02 for "
                                  "tum, 0.01 for nearest)");
  cmd->add_option("--offset", args->offset,
                  "Seconds added to the estimate's stamps before association, in [-1e10, 1e10]")
      ->capture_default_str();
  cmd->add_option("--rpe-delta", args->rpe_delta, "RPE step between compared poses, in (0, 1e9] (whole in frames)")
      ->capture_default_str();
  cmd->add_option("--rpe-unit", args->rpe_unit, "Unit of --rpe-delta: frames, s or m (path travelled)")
      ->capture_default_str();
  cmd->add_flag("--rpe-all-pairs", args->rpe_all_pairs,
                "Start an RPE pair at every pose (default: consecutive, non-overlapping steps as evo)");
  cmd->add_option("--duplicate-stamps", args->duplicate_stamps,
                  "A stamp repeated with a different pose: last (keep the later line with a warning, as TUM's "
                  "associate.py; the TUM fr2/desk ground truth has one) or error (refuse the file)")
      ->check(CLI::IsMember({"error", "last"}))
      ->capture_default_str();
  cmd->add_option("--json", args->json, "Write the results as JSON to this file");
  cmd->add_option("--plot", args->plot, "Write SVG plots: FILE (trajectory view) and FILE_error (APE over time)");
  cmd->callback([args, max_dt] {
    args->max_dt_given = max_dt->count() > 0;
    run_eval(*args);
  });
}

}  // namespace stillslam::apps
