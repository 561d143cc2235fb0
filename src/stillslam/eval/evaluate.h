#pragma once
// One-call trajectory evaluation: associate stamps, align, then absolute
// (APE, translation) and relative (RPE, translation and rotation) errors.
// The `stillslam eval` command, run summaries and benchmarks all use this.
#include <filesystem>
#include <vector>

#include "stillslam/eval/alignment.h"
#include "stillslam/eval/association.h"
#include "stillslam/eval/error_statistics.h"
#include "stillslam/eval/metrics.h"
#include "stillslam/eval/pose_pairs.h"
#include "stillslam/io/trajectory.h"

namespace stillslam {

struct EvaluationOptions {
  AssociationOptions association;
  AlignmentType alignment = AlignmentType::Se3;  // Sim3 for monocular runs
  PosePairOptions rpe;                           // default: 1-frame consecutive steps
};

struct EvaluationResult {
  std::size_t gt_poses = 0;
  std::size_t est_poses = 0;
  std::size_t pairs = 0;  // associated poses
  // The associated sequences: gt[k] and est_aligned[k] share an instant;
  // est_aligned is the estimate moved into the ground-truth frame (the RPE
  // uses it too, so a Sim3 scale also corrects relative translations).
  Trajectory gt;
  Trajectory est_aligned;
  Alignment alignment;
  std::vector<double> ape;  // metres, one per associated pose
  ErrorStatistics ape_stats;
  std::vector<PosePair> rpe_pairs;  // indices into gt / est_aligned
  RelativeErrors rpe;
  ErrorStatistics rpe_trans_stats;  // metres
  ErrorStatistics rpe_rot_stats;    // degrees
};

// Error when no stamps associate (naming max_dt) or alignment is impossible.
// An RPE delta longer than the sequence leaves the RPE empty (count 0, NaN
// values) with a warning. OptionError for NaN or negative max_dt, non-finite offset.
EvaluationResult evaluate(const Trajectory& gt, const Trajectory& est, const EvaluationOptions& options);

// Reads both files (formats detected; see io/trajectory.h) and evaluates them.
EvaluationResult evaluate_files(const std::filesystem::path& gt_path, const std::filesystem::path& est_path,
                                const EvaluationOptions& options);

}  // namespace stillslam
