#include "stillslam/sim/sequence_writer.h"

#include <cmath>
#include <fstream>
#include <future>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/text_file.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/sim/settings_files.h"
#include "stillslam/sim/simulator.h"

namespace stillslam::sim {
namespace fs = std::filesystem;
namespace {

constexpr double kDepthFactor = 5000.0;

// Seconds with 6 decimals from integer nanoseconds (exact, no float rounding).
std::string tum_stamp(std::int64_t ns) {
  const std::int64_t us = ns / 1000;
  return cv::format("%lld.%06lld", static_cast<long long>(us / 1000000),
                    static_cast<long long>(us % 1000000));
}

void write_png(const fs::path& file, const cv::Mat& img) {
  // Fast zlib level: the files are big anyway, and writing must keep up with rendering.
  if (!cv::imwrite(file.string(), img, {cv::IMWRITE_PNG_COMPRESSION, 1})) {
    throw Error("cannot write image " + file.string());
  }
}

cv::Mat depth_png(const cv::Mat& depth) {
  cv::Mat d16;
  // Depth beyond 13.1 m does not fit 16 bits: drop it (0 = no data) instead of clipping.
  cv::Mat valid = depth < (65535.0 / kDepthFactor);
  depth.convertTo(d16, CV_16UC1, kDepthFactor);
  d16.setTo(0, ~valid);
  return d16;
}

}  // namespace

SequenceSummary write_sequence(const fs::path& dir, const SimulationOptions& options,
                               const std::function<void(int, int)>& progress) {
  Stopwatch total;
  const Simulator sim(options);
  const SimulationOptions& o = sim.options();
  const fs::path mav = dir / "mav0";
  if (fs::exists(dir / "rgb.txt") || fs::exists(mav / "cam0" / "data.csv")) {
    if (!o.overwrite) {
      throw Error(dir.string() + " already holds a sequence; choose another --out folder or pass --overwrite");
    }
    // Only what a previous run wrote: stale frames would otherwise linger.
    for (const fs::path& sub : {dir / "rgb", dir / "depth", dir / "masks", dir / "instances", mav / "cam0" / "data",
                                mav / "cam1" / "data"}) {
      fs::remove_all(sub);
    }
  }
  for (const char* sub : {"rgb", "depth", "masks", "instances"}) fs::create_directories(dir / sub);
  if (o.stereo) {
    for (const char* cam : {"cam0", "cam1"}) fs::create_directories(mav / cam / "data");
    fs::create_directories(mav / "state_groundtruth_estimate0");
  }
  const fs::path model = o.segmentation_model.empty()
                             ? fs::weakly_canonical(o.data_dir / ".." / "models" / "yolo11n-seg_384x512.onnx")
                             : fs::absolute(o.segmentation_model);
  SequenceSummary summary;
  summary.settings = dir / "settings.yaml";
  write_rgbd_settings(summary.settings, sim.camera(), o, model);
  if (o.stereo) {
    summary.settings_stereo = dir / "settings_stereo.yaml";
    write_stereo_settings(summary.settings_stereo, sim.camera(), o, model);
    write_euroc_sensor_yaml(mav / "cam0" / "sensor.yaml", sim.camera(), 0.0, o.fps, 0);
    write_euroc_sensor_yaml(mav / "cam1" / "sensor.yaml", sim.camera(), o.baseline, o.fps, 1);
  }

  {
    auto instances_txt = open_for_writing(dir / "instances.txt");
    instances_txt << "# stillslam simulate: what each id of instances/<t>.png stands for\n"
                     "# moved objects (box, chair) carry their id only in the frames where they move\n"
                     "# id kind class moves\n";
    for (const InstanceInfo& i : sim.dynamic_objects().instances()) {
      instances_txt << i.id << " " << i.kind << " " << i.category << " " << (i.moves ? 1 : 0) << "\n";
    }
  }
  auto rgb_txt = open_for_writing(dir / "rgb.txt");
  auto depth_txt = open_for_writing(dir / "depth.txt");
  auto assoc_txt = open_for_writing(dir / "associations.txt");
  rgb_txt << "# color images\n# file: 'stillslam simulate'\n# timestamp filename\n";
  depth_txt << "# depth maps\n# file: 'stillslam simulate'\n# timestamp filename\n";
  std::ofstream cam0_csv, cam1_csv;
  if (o.stereo) {
    cam0_csv = open_for_writing(mav / "cam0" / "data.csv");
    cam1_csv = open_for_writing(mav / "cam1" / "data.csv");
    cam0_csv << "#timestamp [ns],filename\n";
    cam1_csv << "#timestamp [ns],filename\n";
  }
  Trajectory groundtruth;
  double render_ms = 0;
  std::future<void> pending;  // PNG encoding of the previous frame overlaps rendering
  const int n = sim.frame_count();
  for (int i = 0; i < n; ++i) {
    Stopwatch sw;
    SimFrame f = sim.render_frame(i);
    render_ms += sw.elapsed_ms();
    if (pending.valid()) pending.get();
    const std::string t = tum_stamp(f.stamp_ns);
    const std::string ns = std::to_string(f.stamp_ns);
    rgb_txt << t << " rgb/" << t << ".png\n";
    depth_txt << t << " depth/" << t << ".png\n";
    assoc_txt << t << " rgb/" << t << ".png " << t << " depth/" << t << ".png\n";
    if (o.stereo) {
      cam0_csv << ns << "," << ns << ".png\n";
      cam1_csv << ns << "," << ns << ".png\n";
    }
    groundtruth.push_back({std::stod(t), f.T_world_cam});
    pending = std::async(std::launch::async, [&dir, &mav, t, ns, stereo = o.stereo, gray = o.stereo_gray,
                                              f = std::move(f)] {
      write_png(dir / "rgb" / (t + ".png"), f.bgr);
      write_png(dir / "depth" / (t + ".png"), depth_png(f.depth));
      write_png(dir / "masks" / (t + ".png"), f.mask);
      write_png(dir / "instances" / (t + ".png"), f.dynamic_ids);
      if (stereo) {
        cv::Mat left = f.bgr;
        if (gray) cv::cvtColor(f.bgr, left, cv::COLOR_BGR2GRAY);
        write_png(mav / "cam0" / "data" / (ns + ".png"), left);
        write_png(mav / "cam1" / "data" / (ns + ".png"), gray ? f.right_gray : f.right_bgr);
      }
    });
    if (progress) progress(i + 1, n);
  }
  if (pending.valid()) pending.get();
  write_trajectory(dir / "groundtruth.txt", groundtruth, TrajectoryFormat::Tum);
  if (o.stereo) {
    // Written here, not with io's writer: stamps must equal the image names to the nanosecond.
    auto gt = open_for_writing(mav / "state_groundtruth_estimate0" / "data.csv");
    gt << "#timestamp [ns],p_x [m],p_y [m],p_z [m],q_w [],q_x [],q_y [],q_z []\n";
    for (int i = 0; i < n; ++i) {
      const Eigen::Isometry3d T = sim.pose(i);
      const Eigen::Quaterniond q(T.linear());
      gt << sim.stamp_ns(i)
         << cv::format(",%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f\n", T.translation().x(), T.translation().y(),
                       T.translation().z(), q.w(), q.x(), q.y(), q.z());
    }
  }
  summary.frames = n;
  summary.render_ms_mean = n > 0 ? render_ms / n : 0;
  summary.seconds = total.elapsed_ms() / 1000.0;
  return summary;
}

}  // namespace stillslam::sim
