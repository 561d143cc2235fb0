#pragma once
// The pieces of the HTML run report (run_report.h), each an HTML fragment:
// SVG figures (run_report_plots.cpp), the 3D view (run_report_3d.cpp) and the
// strip of saved frames (run_report_strip.cpp).
#include <string>
#include <vector>

#include "stillslam/benchmark/run_report.h"

namespace stillslam {

// Series colour of run k (the ground truth is dark gray).
std::string report_run_color(std::size_t k);
inline constexpr const char* kReportGroundTruthColor = "#444444";

// Over all runs: trajectories from above (aligned), APE and translational RPE over time.
std::string report_trajectory_svg(const std::vector<ReportRun>& runs, const Trajectory& groundtruth);
std::string report_ape_svg(const std::vector<ReportRun>& runs);
std::string report_rpe_svg(const std::vector<ReportRun>& runs);

// One run: time per frame stacked by stage, features kept and removed, mask
// coverage, and the tracking state timeline (lost frames, relocalizations,
// keyframes, new maps).
std::string report_timing_svg(const ReportRun& run);
std::string report_features_svg(const ReportRun& run);
std::string report_mask_svg(const ReportRun& run);
std::string report_state_timeline_svg(const ReportRun& run);

// A <canvas> and a script drawing the ground truth and the aligned runs in 3D,
// orbited with the mouse (drag: rotate, wheel: zoom). Sets data-drawn on the
// canvas to the number of polylines drawn.
std::string report_3d_view(const std::vector<ReportRun>& runs, const Trajectory& groundtruth);

// Up to `count` of the run's saved frames, evenly spaced, as inline JPEG <figure>s `width` wide.
std::string report_frame_strip(const ReportRun& run, int count, int width);

}  // namespace stillslam
