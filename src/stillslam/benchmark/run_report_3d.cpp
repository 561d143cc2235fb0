// The orbitable 3D trajectory view of the HTML run report (run_report_parts.h):
// the positions as inline JSON and a small script that projects them on a
// canvas; no library, nothing from the network.
#include <cstdio>

#include "stillslam/benchmark/html_text.h"
#include "stillslam/benchmark/run_report_parts.h"

namespace stillslam {
namespace {

std::string positions_json(const Trajectory& poses) {
  std::string out = "[";
  char buf[96];
  for (const StampedPose& p : poses) {
    const Eigen::Vector3d c = p.T_world_cam.translation();
    std::snprintf(buf, sizeof(buf), "%s[%.4f,%.4f,%.4f]", out.size() > 1 ? "," : "", c.x(), c.y(), c.z());
    out += buf;
  }
  return out + "]";
}

// Drag rotates (yaw about the vertical world axis, pitch), the wheel zooms.
// Coordinates are centred on the data and scaled to the canvas.
constexpr const char* kOrbitScript = R"JS(
(function () {
  const canvas = document.getElementById('view3d');
  const data = JSON.parse(document.getElementById('view3d-data').textContent);
  const ctx = canvas.getContext('2d');
  const all = [].concat(...data.lines.map(l => l.points));
  if (all.length === 0) { canvas.dataset.drawn = '0'; return; }
  const lo = [0, 1, 2].map(a => all.reduce((m, p) => Math.min(m, p[a]), Infinity));
  const hi = [0, 1, 2].map(a => all.reduce((m, p) => Math.max(m, p[a]), -Infinity));
  const centre = lo.map((v, a) => 0.5 * (v + hi[a]));
  const radius = Math.max(1e-6, ...hi.map((v, a) => v - lo[a])) * 0.75;
  let yaw = 0.6, pitch = 0.5, zoom = 1.0, drag = null;
  function project(p) {
    const x = p[0] - centre[0], y = p[1] - centre[1], z = p[2] - centre[2];
    const cx = Math.cos(yaw) * x - Math.sin(yaw) * z, cz = Math.sin(yaw) * x + Math.cos(yaw) * z;
    const cy = Math.cos(pitch) * y - Math.sin(pitch) * cz, d = Math.sin(pitch) * y + Math.cos(pitch) * cz;
    const s = zoom * 0.45 * Math.min(canvas.width, canvas.height) / radius / (1 + 0.15 * d / radius);
    return [canvas.width / 2 + s * cx, canvas.height / 2 + s * cy];
  }
  function draw() {
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    let drawn = 0;
    for (const line of data.lines) {
      ctx.strokeStyle = line.color;
      ctx.lineWidth = line.dashed ? 1 : 2;
      ctx.setLineDash(line.dashed ? [6, 4] : []);
      ctx.beginPath();
      line.points.forEach((p, i) => { const q = project(p); if (i) ctx.lineTo(q[0], q[1]); else ctx.moveTo(q[0], q[1]); });
      ctx.stroke();
      drawn += line.points.length > 0 ? 1 : 0;
    }
    ctx.setLineDash([]);
    ctx.fillStyle = '#333';
    ctx.font = '12px sans-serif';
    ctx.fillText('drag to orbit, wheel to zoom', 8, canvas.height - 8);
    canvas.dataset.drawn = String(drawn);
  }
  canvas.addEventListener('mousedown', e => { drag = [e.clientX, e.clientY]; });
  window.addEventListener('mouseup', () => { drag = null; });
  window.addEventListener('mousemove', e => {
    if (!drag) return;
    yaw += 0.01 * (e.clientX - drag[0]);
    pitch = Math.max(-1.5, Math.min(1.5, pitch + 0.01 * (e.clientY - drag[1])));
    drag = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener('wheel', e => { e.preventDefault(); zoom *= e.deltaY < 0 ? 1.1 : 1 / 1.1; draw(); });
  draw();
})();
)JS";

}  // namespace

std::string report_3d_view(const std::vector<ReportRun>& runs, const Trajectory& groundtruth) {
  std::string lines;
  auto add = [&lines](const std::string& label, const std::string& color, bool dashed, const Trajectory& poses) {
    if (!lines.empty()) lines += ",";
    // The label goes into a <script type="application/json">: no "</" in it.
    std::string safe;
    for (char c : label) safe += c == '"' || c == '\\' || c == '<' || static_cast<unsigned char>(c) < 32 ? ' ' : c;
    lines += "{\"label\":\"" + safe + "\",\"color\":\"" + color + "\",\"dashed\":" + (dashed ? "true" : "false") +
             ",\"points\":" + positions_json(poses) + "}";
  };
  if (!groundtruth.empty()) {
    // Only the span the main run covers, as in the top view.
    Trajectory span = groundtruth;
    if (!runs.empty() && runs.front().evaluation && !runs.front().evaluation->gt.empty()) span = runs.front().evaluation->gt;
    add("ground truth", kReportGroundTruthColor, true, span);
  }
  for (std::size_t k = 0; k < runs.size(); ++k) {
    add(runs[k].label, report_run_color(k), false, runs[k].evaluation ? runs[k].evaluation->est_aligned : runs[k].trajectory);
  }
  return "<canvas id=\"view3d\" width=\"800\" height=\"500\"></canvas>\n"
         "<script type=\"application/json\" id=\"view3d-data\">{\"lines\":[" + lines + "]}</script>\n"
         "<script>" + std::string(kOrbitScript) + "</script>\n";
}

}  // namespace stillslam
