#pragma once
// The two standard evaluation figures as SVG: the aligned estimate over the
// ground truth seen from above, and the APE over time.
#include <filesystem>
#include <string>

#include "stillslam/eval/evaluate.h"

namespace stillslam {

// Projects onto the two world axes along which the ground truth spreads most
// (x-y for most ground vehicles, x-z for TUM's camera frames, ...).
std::string trajectory_view_svg(const EvaluationResult& result);

// APE per associated pose against seconds since the first pose, with its rmse.
std::string ape_over_time_svg(const EvaluationResult& result);

// Writes trajectory_view_svg to `path` and ape_over_time_svg next to it with
// an "_error" suffix (plot.svg -> plot_error.svg). Returns the second path.
std::filesystem::path write_evaluation_plots(const std::filesystem::path& path, const EvaluationResult& result);

}  // namespace stillslam
