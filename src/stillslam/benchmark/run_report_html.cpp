// The HTML document of the run report (run_report.h): summary with ids,
// figures, events, per-run sections and the settings used.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "stillslam/benchmark/html_text.h"
#include "stillslam/benchmark/run_report_parts.h"

namespace stillslam {
namespace {

constexpr const char* kReportStyle = R"CSS(
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1100px; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.8em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; } td, th { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
td:first-child, th:first-child { text-align: left; }
svg { max-width: 100%; height: auto; display: block; margin: 0.5em 0; }
canvas { border: 1px solid #ccc; max-width: 100%; cursor: grab; }
.strip { display: flex; flex-wrap: wrap; gap: 6px; } figure { margin: 0; font-size: 0.75em; }
img.frame { display: block; max-width: 260px; }
pre { background: #f6f6f6; padding: 0.6em; overflow-x: auto; font-size: 0.85em; }
.swatch { display: inline-block; width: 1em; height: 0.8em; margin-right: 0.3em; }
)CSS";

std::string fixed_text(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

std::string cell(const std::string& id, const std::string& text) {
  return "<td id=\"" + id + "\">" + text + "</td>";
}

struct FrameCounts {
  std::size_t processed = 0, tracked = 0, lost = 0, relocalized = 0;
};

FrameCounts count_frames(const ReportRun& run) {
  FrameCounts c;
  for (const nlohmann::json& f : run.stats["frames"]) {
    ++c.processed;
    c.tracked += f.value("has_pose", false) ? 1 : 0;
    c.lost += f.value("state", "") == "lost" ? 1 : 0;
    c.relocalized += f.value("reason", "") == "relocalized" ? 1 : 0;
  }
  return c;
}

double median_total_ms(const ReportRun& run) {
  std::vector<double> v;
  for (const nlohmann::json& f : run.stats["frames"]) {
    if (f.contains("times_ms")) v.push_back(f["times_ms"].value("total", 0.0));
  }
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string summary_table(const std::vector<ReportRun>& runs) {
  std::string html =
      "<table id=\"summary\"><tr><th>run</th><th>ATE rmse [m]</th><th>poses evaluated</th><th>frames "
      "processed</th><th>frames in input</th><th>tracked</th><th>lost</th><th>keyframes</th><th>relocalizations</th>"
      "<th>median ms/frame</th></tr>\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const ReportRun& r = runs[k];
    const std::string n = std::to_string(k);
    const FrameCounts c = count_frames(r);
    std::size_t in_input = c.processed;
    if (r.stats.contains("end")) in_input = r.stats["end"].value("frames_in_input", in_input);
    html += "<tr><td><span class=\"swatch\" style=\"background:" + report_run_color(k) + "\"></span>" +
            html_escape(r.label) + "</td>";
    html += r.evaluation ? cell("ate-rmse-" + n, fixed_text(r.evaluation->ape_stats.rmse, 6))
                         : cell("ate-rmse-" + n, "n/a (" + html_escape(r.evaluation_error) + ")");
    html += cell("ate-pairs-" + n, r.evaluation ? std::to_string(r.evaluation->pairs) : "0");
    html += cell("frames-" + n, std::to_string(c.processed));
    html += cell("frames-in-input-" + n, std::to_string(in_input));
    html += cell("tracked-" + n, std::to_string(c.tracked));
    html += cell("lost-" + n, std::to_string(c.lost));
    html += cell("keyframes-" + n, std::to_string(r.keyframes));
    html += cell("relocalizations-" + n, std::to_string(c.relocalized));
    html += cell("median-ms-" + n, fixed_text(median_total_ms(r), 2)) + "</tr>\n";
  }
  return html + "</table>\n";
}

// Lost stretches, relocalizations and map changes, in frame order.
std::string events_list(const ReportRun& run) {
  const nlohmann::json& frames = run.stats["frames"];
  std::vector<std::string> events;
  std::size_t lost_start = 0;
  bool lost = false;
  std::uint64_t map_id = frames.empty() ? 0 : frames[0].value("map_id", std::uint64_t{0});
  for (std::size_t i = 0; i <= frames.size(); ++i) {
    const bool now = i < frames.size() && frames[i].value("state", "") == "lost";
    if (now && !lost) lost_start = i;
    if (!now && lost) {
      events.push_back("tracking lost: frames " + std::to_string(frames[lost_start].value("index", 0)) + " to " +
                       std::to_string(frames[i - 1].value("index", 0)) + " (" + std::to_string(i - lost_start) +
                       " frames)");
    }
    lost = now;
    if (i == frames.size()) break;
    const int index = frames[i].value("index", 0);
    if (frames[i].value("reason", "") == "relocalized") events.push_back("relocalized at frame " + std::to_string(index));
    const std::uint64_t id = frames[i].value("map_id", std::uint64_t{0});
    if (id != map_id) events.push_back("active map " + std::to_string(map_id) + " -> " + std::to_string(id) +
                                       " at frame " + std::to_string(index));
    map_id = id;
  }
  if (events.empty()) return "<p>No tracking loss, relocalization or map change.</p>\n";
  std::string html = "<ul class=\"events\">";
  for (const std::string& e : events) html += "<li>" + html_escape(e) + "</li>";
  return html + "</ul>\n";
}

std::string settings_section(const ReportRun& run) {
  std::string html = "<table class=\"settings\">";
  for (const char* key : {"config", "input", "groundtruth", "segmentation", "deterministic", "vocabulary",
                          "loop_closing", "localization_only", "load_map"}) {
    if (!run.stats.contains(key)) continue;
    const nlohmann::json& v = run.stats[key];
    html += "<tr><td>" + std::string(key) + "</td><td>" +
            html_escape(v.is_string() ? v.get<std::string>() : v.dump()) + "</td></tr>";
  }
  html += "</table>\n";
  if (run.stats.contains("config") && run.stats["config"].is_string()) {
    const std::string path = run.stats["config"].get<std::string>();
    std::ifstream in(path);
    if (in) {
      std::ostringstream text;
      text << in.rdbuf();
      html += "<p>Settings file " + html_escape(path) + " (as it is now):</p><pre>" + html_escape(text.str()) +
              "</pre>\n";
    } else {
      html += "<p>The settings file " + html_escape(path) + " can no longer be read.</p>\n";
    }
  }
  return html;
}

}  // namespace

std::string render_run_report(const std::vector<ReportRun>& runs, const Trajectory& groundtruth,
                              const std::string& groundtruth_name, const RunReportOptions& options) {
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>stillslam report: " +
                     html_escape(runs.front().label) + "</title><style>" + kReportStyle + "</style></head><body>\n";
  html += "<h1>stillslam run report</h1>\n<p>Run folder <code id=\"run-dir\">" + html_escape(runs.front().dir.string()) +
          "</code>";
  for (std::size_t k = 1; k < runs.size(); ++k) html += ", compared with <code>" + html_escape(runs[k].dir.string()) + "</code>";
  html += ". Ground truth: " + (groundtruth_name.empty() ? std::string("none") : html_escape(groundtruth_name)) +
          ". ATE is the rmse of the position error after SE3 alignment (greedy association within 0.02 s), as "
          "<code>stillslam eval</code> computes by default.</p>\n";
  html += "<h2>Summary</h2>\n" + summary_table(runs);
  html += "<h2>Trajectory</h2>\n" + report_trajectory_svg(runs, groundtruth);
  html += "<h3>3D view</h3>\n" + report_3d_view(runs, groundtruth);
  html += "<h2>Errors over time</h2>\n" + report_ape_svg(runs) + report_rpe_svg(runs);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const ReportRun& r = runs[k];
    html += "<h2 id=\"run-" + std::to_string(k) + "\">Run " + std::to_string(k) + ": " + html_escape(r.label) +
            "</h2>\n";
    html += "<h3>Tracking state</h3>\n" + report_state_timeline_svg(r) + events_list(r);
    html += "<h3>Time per frame</h3>\n" + report_timing_svg(r);
    html += "<h3>Dynamic filter</h3>\n" + report_features_svg(r) + report_mask_svg(r);
    html += "<h3>Frames</h3>\n";
    if (r.saved_frames.empty()) {
      html += "<p>No saved frames (run with <code>--save-frames " + html_escape((r.dir / "frames").string()) +
              "</code> to see them here).</p>\n";
    } else {
      html += "<p>" + std::to_string(r.saved_frames.size()) +
              " saved frames; kept features green (tracked) or amber, removed features red, dynamic masks "
              "magenta.</p>\n" +
              report_frame_strip(r, options.strip_frames, options.strip_width);
    }
    html += "<h3>Settings</h3>\n" + settings_section(r);
  }
  return html + "</body></html>\n";
}

}  // namespace stillslam
