// Where moving points get into tracking and the map, counted with a
// `stillslam simulate` folder's exact masks (issue #20). One run of the
// system (segmentation off unless --oracle-masks: the ORB-SLAM-like core);
// a TrackingProbe sees every tracking stage and does not change it.
//
//   build/bench/bench_dynamic_points --config S.yaml --input SIMDIR [--oracle-masks]
//       [--deterministic] [--max-frames N] [--window N] [--json OUT]
//       [--oracle-instances] [--matches-csv OUT]
//
// --oracle-instances: segmentation on with the folder's instances/ (one
// detection per instance, as bench_slam --oracle-instances) instead of masks/.
// --matches-csv: one row per local-map match of every frame (frame, keypoint
// pixel and octave, outlier flag, the frame's depth there, the map point's id,
// position, first keyframe's frame and observation count, the frame's tracked
// pose, the keypoint's distance to the exact mask, and with --twin the depth
// of the same path without movers at the keypoint), to check each match
// against the ground truth offline.
//
// "Dynamic" keypoint: within --margin px of the frame's ground-truth mask.
// Per stage (motion model, reference keyframe, lost, local map): matches and
// inliers, and how many of them are dynamic; of those, the matches whose map
// point has static evidence (tracking/static_evidence.h: they alone move the
// pose), and the stages where too few had it and the pose came from all
// matches (the fallback). Per keyframe: depth points
// created on dynamic pixels. The map is scanned at each keyframe: every new
// map point (from keyframe depth or local-mapping triangulation) is classed
// by the pixel it was first observed at, and its lifetime (keyframes until it
// was culled) is recorded. Per window of frames: the drift of the tracked
// (raw) pose against the ground truth, both taken relative to the first
// tracked frame, next to the dynamic share of the inliers.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <unordered_map>

#include "oracle_instance_segmenter.h"
#include "oracle_segmenter.h"
#include "stillslam/io/trajectory.h"
#include "stillslam/settings/settings.h"
#include "stillslam/system/dataset_runner.h"
#include "stillslam/tracking/static_evidence.h"

namespace fs = std::filesystem;
using namespace stillslam;

namespace {

struct Args {
  std::string config, input, json, groundtruth, matches_csv, twin;
  double depth_factor = 5000;
  bool oracle = false, oracle_instances = false, deterministic = false;
  std::size_t max_frames = 0;
  int window = 30;
  int margin = 2;
};

struct StageCount {
  int frames = 0;
  long matches = 0, dynamic_matches = 0, inliers = 0, dynamic_inliers = 0;
  // Matches with static evidence; "born dynamic": the map point was made on a
  // dynamic pixel (not a static point mismatched onto a moving thing).
  long evidence = 0, evidence_dynamic = 0, evidence_inliers = 0, evidence_dynamic_inliers = 0;
  long evidence_born_dynamic_inliers = 0;
  int fallbacks = 0;
};

struct FrameRecord {
  std::uint64_t id = 0;
  int local_inliers = -1, local_dynamic_inliers = 0, local_matches = 0, local_dynamic_matches = 0;
  int keyframe_new_points = 0, keyframe_new_dynamic = 0;
  int first_matches = 0, first_dynamic_matches = 0, first_inliers = 0, first_dynamic_inliers = 0;  // motion model / reference / lost
  // Static-evidence matches of the first stage and of the local map: matches,
  // dynamic, inliers, dynamic inliers, born-dynamic inliers; fallback flags.
  std::array<int, 5> first_evidence{}, local_evidence{};
  bool first_fallback = false, local_fallback = false;
  bool keyframe = false;
  std::optional<Eigen::Isometry3d> T_world_cam;
  double drift = -1;
  Eigen::Vector3d est = Eigen::Vector3d::Zero(), truth = Eigen::Vector3d::Zero();  // relative to the first frame
};

struct PointLife {
  bool dynamic = false;
  std::uint64_t first_keyframe = 0;
  std::optional<std::uint64_t> culled_at_keyframe;  // first scan that did not find it
};

class DynamicCounter {
 public:
  DynamicCounter(std::vector<cv::Mat1b> masks, StaticEvidenceOptions evidence)
      : masks_(std::move(masks)), evidence_(evidence) {}

  bool dynamic(std::uint64_t frame, const cv::KeyPoint& kp) const {
    if (frame >= masks_.size()) return false;
    const cv::Mat1b& m = masks_[frame];
    const int x = static_cast<int>(std::lround(kp.pt.x)), y = static_cast<int>(std::lround(kp.pt.y));
    return x >= 0 && y >= 0 && x < m.cols && y < m.rows && m(y, x) != 0;
  }

  // `mask_files`: the exact masks (undilated) for the distance column;
  // `twin_depth`: depth images of the same path without the movers (may be empty).
  void dump_matches_to(std::ofstream* out, std::vector<fs::path> mask_files, std::vector<fs::path> twin_depth,
                       double depth_factor) {
    csv_ = out;
    mask_files_ = std::move(mask_files);
    twin_depth_ = std::move(twin_depth);
    depth_factor_ = depth_factor;
  }

  void on_stage(TrackingStage stage, const Frame& frame, const Map& map) {
    FrameRecord& r = record(frame.id());
    if (stage == TrackingStage::NewKeyFrame) {
      if (const KeyFramePtr& kf = frame.reference_keyframe()) keyframe_frames_[kf->id()] = frame.id();
      on_keyframe(frame, map, r);
      return;
    }
    if (stage == TrackingStage::LocalMap && csv_) write_matches(frame);
    StageCount& c = stages_[stage];
    ++c.frames;
    int matches = 0, dyn_matches = 0, inliers = 0, dyn_inliers = 0;
    std::array<int, 5> ev{};
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const MapPointPtr& mp = frame.map_point(i);
      if (!mp) continue;
      const bool dyn = dynamic(frame.id(), frame.keypoint(i));
      ++matches;
      dyn_matches += dyn;
      if (!frame.is_outlier(i)) {
        ++inliers;
        dyn_inliers += dyn;
      }
      if (!has_static_evidence(*mp, evidence_)) continue;
      ++ev[0];
      ev[1] += dyn;
      if (frame.is_outlier(i)) continue;
      ++ev[2];
      ev[3] += dyn;
      const auto life = points_.find(mp->id());
      ev[4] += dyn && life != points_.end() && life->second.dynamic;
    }
    // As refine_pose_on_evidence decides (the inlier test after the fact:
    // with the fallback the flags come from the all-match optimization).
    const bool fallback = evidence_.enabled && stage != TrackingStage::Lost &&
                          (ev[0] < evidence_.min_points || ev[2] < evidence_.min_points);
    c.evidence += ev[0];
    c.evidence_dynamic += ev[1];
    c.evidence_inliers += ev[2];
    c.evidence_dynamic_inliers += ev[3];
    c.evidence_born_dynamic_inliers += ev[4];
    c.fallbacks += fallback;
    c.matches += matches;
    c.dynamic_matches += dyn_matches;
    c.inliers += inliers;
    c.dynamic_inliers += dyn_inliers;
    if (stage != TrackingStage::LocalMap) {
      r.first_matches = matches;
      r.first_dynamic_matches = dyn_matches;
      r.first_inliers = inliers;
      r.first_dynamic_inliers = dyn_inliers;
      r.first_evidence = ev;
      r.first_fallback = fallback;
    } else {
      r.local_matches = matches;
      r.local_dynamic_matches = dyn_matches;
      r.local_inliers = inliers;
      r.local_dynamic_inliers = dyn_inliers;
      r.local_evidence = ev;
      r.local_fallback = fallback;
      r.T_world_cam = frame.T_cam_world().inverse();
    }
  }

  const std::map<TrackingStage, StageCount>& stages() const { return stages_; }
  std::vector<FrameRecord>& frames() { return frames_; }
  const std::unordered_map<std::uint64_t, PointLife>& points() const { return points_; }
  std::uint64_t keyframes_seen() const { return keyframes_; }
  // Per keyframe scan: alive points, of which dynamic.
  const std::vector<std::pair<int, int>>& alive() const { return alive_; }

 private:
  FrameRecord& record(std::uint64_t id) {
    if (frames_.empty() || frames_.back().id != id) {
      frames_.push_back({});
      frames_.back().id = id;
    }
    return frames_.back();
  }

  void on_keyframe(const Frame& frame, const Map& map, FrameRecord& r) {
    ++keyframes_;
    r.keyframe = true;
    const KeyFramePtr& kf = frame.reference_keyframe();
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const MapPointPtr& mp = frame.map_point(i);
      if (!mp || !kf || mp->first_keyframe_id() != kf->id()) continue;
      ++r.keyframe_new_points;
      r.keyframe_new_dynamic += dynamic(frame.id(), frame.keypoint(i));
    }
    // Scan the map: class new points by their first observation, close the
    // lives of points that are gone.
    std::unordered_map<std::uint64_t, bool> present;
    int alive = 0, alive_dynamic = 0;
    for (const MapPointPtr& mp : map.map_points()) {
      if (mp->is_bad()) continue;
      present[mp->id()] = true;
      auto it = points_.find(mp->id());
      if (it == points_.end()) {
        PointLife life;
        life.first_keyframe = mp->first_keyframe_id();
        const MapPoint::Observations& obs = mp->observations();
        if (obs.empty()) continue;
        // The creating keyframe's observation if it is still there, else the earliest.
        auto o = obs.begin();
        for (auto k = obs.begin(); k != obs.end(); ++k) {
          if (k->first->id() == mp->first_keyframe_id()) o = k;
        }
        life.dynamic = dynamic(o->first->frame_id(), o->first->keypoint(o->second));
        it = points_.emplace(mp->id(), life).first;
      }
      ++alive;
      alive_dynamic += it->second.dynamic;
    }
    for (auto& [id, life] : points_) {
      if (!life.culled_at_keyframe && !present.count(id)) life.culled_at_keyframe = kf ? kf->id() : 0;
    }
    alive_.emplace_back(alive, alive_dynamic);
  }

  void write_matches(const Frame& frame) {
    // Distance of each pixel to the nearest exact-mask pixel; the twin's depth.
    cv::Mat1f distance;
    if (frame.id() < mask_files_.size()) {
      const cv::Mat1b m = cv::imread(mask_files_[frame.id()].string(), cv::IMREAD_GRAYSCALE) == 0;
      cv::distanceTransform(m, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    }
    cv::Mat twin;
    if (frame.id() < twin_depth_.size()) twin = cv::imread(twin_depth_[frame.id()].string(), cv::IMREAD_UNCHANGED);
    const Eigen::Isometry3d T = frame.T_cam_world();
    const Eigen::Quaterniond q(T.linear());
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const MapPointPtr& mp = frame.map_point(i);
      if (!mp) continue;
      const cv::KeyPoint& kp = frame.keypoint(i);
      const auto born = keyframe_frames_.find(mp->first_keyframe_id());
      const long born_frame = born == keyframe_frames_.end() ? -1 : static_cast<long>(born->second);
      const Eigen::Vector3d& p = mp->position();
      const int x = std::max(0, static_cast<int>(std::lround(kp.pt.x)));
      const int y = std::max(0, static_cast<int>(std::lround(kp.pt.y)));
      const float dist = !distance.empty() && x < distance.cols && y < distance.rows ? distance(y, x) : -1.f;
      const double twin_z = !twin.empty() && x < twin.cols && y < twin.rows
                                ? static_cast<double>(twin.at<std::uint16_t>(y, x)) / depth_factor_
                                : -1.0;
      *csv_ << frame.id() << ',' << kp.pt.x << ',' << kp.pt.y << ',' << kp.octave << ',' << frame.is_outlier(i) << ','
            << frame.depth(i) << ',' << mp->id() << ',' << p.x() << ',' << p.y() << ',' << p.z() << ',' << born_frame
            << ',' << mp->num_observations() << ',' << T.translation().x() << ',' << T.translation().y() << ','
            << T.translation().z() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ',' << q.w() << ',' << dist << ','
            << twin_z << '\n';
    }
  }

  std::ofstream* csv_ = nullptr;
  std::vector<fs::path> mask_files_, twin_depth_;
  double depth_factor_ = 5000;
  std::unordered_map<std::uint64_t, std::uint64_t> keyframe_frames_;  // keyframe id -> frame id
  std::vector<cv::Mat1b> masks_;
  StaticEvidenceOptions evidence_;
  std::map<TrackingStage, StageCount> stages_;
  std::vector<FrameRecord> frames_;
  std::unordered_map<std::uint64_t, PointLife> points_;
  std::vector<std::pair<int, int>> alive_;
  std::uint64_t keyframes_ = 0;
};

double share(long part, long whole) { return whole > 0 ? 100.0 * static_cast<double>(part) / whole : 0.0; }

// The ground-truth pose nearest in time (the simulator writes one per frame).
std::optional<Eigen::Isometry3d> pose_at(const Trajectory& gt, double t) {
  auto it = std::lower_bound(gt.begin(), gt.end(), t, [](const StampedPose& p, double v) { return p.timestamp < v; });
  const StampedPose* best = nullptr;
  if (it != gt.end()) best = &*it;
  if (it != gt.begin() && (!best || std::abs(std::prev(it)->timestamp - t) < std::abs(best->timestamp - t))) {
    best = &*std::prev(it);
  }
  if (!best || std::abs(best->timestamp - t) > 0.005) return std::nullopt;
  return best->T_world_cam;
}

int run(const Args& a) {
  const Settings settings = load_settings(a.config);
  const auto dataset = open_dataset(a.input, settings);
  const std::vector<fs::path> files = oracle::oracle_mask_files(a.input);
  std::vector<cv::Mat1b> masks;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * a.margin + 1, 2 * a.margin + 1));
  for (const fs::path& f : files) {
    cv::Mat1b m = cv::imread(f.string(), cv::IMREAD_GRAYSCALE) > 0;
    if (m.empty()) throw Error(f.string() + ": cannot read the ground-truth mask; is --input a simulate folder?");
    if (a.margin > 0) cv::dilate(m, m, kernel);
    masks.push_back(m);
  }
  DynamicCounter counter(std::move(masks), settings.tracking.static_evidence);

  std::ofstream csv;
  if (!a.matches_csv.empty()) {
    csv.open(a.matches_csv);
    if (!csv) throw Error(a.matches_csv + ": cannot write");
    csv.precision(9);
    csv << "frame,u,v,octave,outlier,depth,point,x,y,z,born_frame,observations,tx,ty,tz,qx,qy,qz,qw,mask_distance,twin_depth\n";
    std::vector<fs::path> twin;
    if (!a.twin.empty()) {
      for (const TumPair& p : read_tum_associations(fs::path(a.twin) / "associations.txt")) {
        twin.push_back(fs::path(a.twin) / p.depth_file);
      }
    }
    counter.dump_matches_to(&csv, oracle::oracle_mask_files(a.input), std::move(twin), a.depth_factor);
  }

  RunOptions options;
  options.system.use_segmentation = a.oracle || a.oracle_instances;
  if (a.oracle_instances) {
    options.system.segmenter_factory = [dir = a.input] { return std::make_unique<oracle::OracleInstanceSegmenter>(dir); };
  } else if (a.oracle) {
    options.system.segmenter_factory = [dir = a.input] { return std::make_unique<oracle::OracleSegmenter>(dir); };
  }
  options.system.deterministic = a.deterministic;
  options.system.tracking_probe = [&counter](TrackingStage s, const Frame& f, const Map& m) { counter.on_stage(s, f, m); };
  if (a.max_frames > 0) options.max_frames = a.max_frames;
  const RunResult r = run_dataset(settings, *dataset, options);
  if (r.error) std::printf("run ended early: %s\n", r.error->c_str());

  // Timestamps of the frames (ids are dataset indices).
  std::vector<double> stamps(r.frames.size());
  for (std::size_t i = 0; i < r.frames.size(); ++i) stamps[i] = r.frames[i].timestamp;
  const fs::path gt_file = a.groundtruth.empty() ? fs::path(a.input) / "groundtruth.txt" : fs::path(a.groundtruth);
  const Trajectory gt = read_trajectory(gt_file);
  std::optional<Eigen::Isometry3d> first_est, first_gt;
  for (FrameRecord& f : counter.frames()) {
    if (!f.T_world_cam || f.id >= stamps.size()) continue;
    const auto g = pose_at(gt, stamps[f.id]);
    if (!g) continue;
    if (!first_est) {
      first_est = *f.T_world_cam;
      first_gt = *g;
    }
    const Eigen::Vector3d e = (first_est->inverse() * *f.T_world_cam).translation();
    const Eigen::Vector3d t = (first_gt->inverse() * *g).translation();
    f.drift = (e - t).norm();
    f.est = e;
    f.truth = t;
  }

  std::printf("%s (%s, segmentation %s, %s; dynamic = within %d px of the exact mask)\n", a.input.c_str(),
              to_string(dataset->sensor()),
              a.oracle_instances ? "on (exact instances)" : a.oracle ? "on (exact masks)" : "off",
              a.deterministic ? "deterministic" : "concurrent local mapping", a.margin);
  nlohmann::json out;
  out["input"] = a.input;
  out["segmentation"] = a.oracle;
  std::printf("  %-20s %6s %9s %7s %9s %7s %12s\n", "stage", "frames", "matches", "dyn %", "inliers", "dyn %",
              "dyn outlier%");
  for (const auto& [stage, c] : counter.stages()) {
    const double dyn_outlier = share(c.dynamic_matches - c.dynamic_inliers, c.dynamic_matches);
    std::printf("  %-20s %6d %9.1f %7.2f %9.1f %7.2f %12.1f\n", to_string(stage), c.frames,
                c.frames ? static_cast<double>(c.matches) / c.frames : 0.0, share(c.dynamic_matches, c.matches),
                c.frames ? static_cast<double>(c.inliers) / c.frames : 0.0, share(c.dynamic_inliers, c.inliers),
                dyn_outlier);
    out["stages"][to_string(stage)] = {{"frames", c.frames},         {"matches", c.matches},
                                       {"dynamic_matches", c.dynamic_matches}, {"inliers", c.inliers},
                                       {"dynamic_inliers", c.dynamic_inliers}, {"evidence", c.evidence},
                                       {"evidence_dynamic", c.evidence_dynamic},
                                       {"evidence_inliers", c.evidence_inliers},
                                       {"evidence_dynamic_inliers", c.evidence_dynamic_inliers},
                                       {"evidence_born_dynamic_inliers", c.evidence_born_dynamic_inliers},
                                       {"fallbacks", c.fallbacks}};
  }
  std::printf("  %-20s %9s %7s %9s %7s %9s %9s\n", "static evidence", "matches", "dyn %", "inliers", "dyn %",
              "born dyn%", "fallbacks");
  for (const auto& [stage, c] : counter.stages()) {
    std::printf("  %-20s %9.1f %7.2f %9.1f %7.2f %9.2f %9d\n", to_string(stage),
                c.frames ? static_cast<double>(c.evidence) / c.frames : 0.0, share(c.evidence_dynamic, c.evidence),
                c.frames ? static_cast<double>(c.evidence_inliers) / c.frames : 0.0,
                share(c.evidence_dynamic_inliers, c.evidence_inliers),
                share(c.evidence_born_dynamic_inliers, c.evidence_inliers), c.fallbacks);
  }
  long kf_points = 0, kf_dynamic = 0;
  for (const FrameRecord& f : counter.frames()) {
    kf_points += f.keyframe_new_points;
    kf_dynamic += f.keyframe_new_dynamic;
  }
  std::printf("  keyframes %llu: %ld depth points created, %ld (%.1f %%) on dynamic pixels\n",
              static_cast<unsigned long long>(counter.keyframes_seen()), kf_points, kf_dynamic, share(kf_dynamic, kf_points));
  // The map's start: how many of the first keyframe's points lie on movers.
  for (const FrameRecord& f : counter.frames()) {
    if (!f.keyframe) continue;
    std::printf("  first keyframe (frame %llu): %d points, %d (%.1f %%) on dynamic pixels\n",
                static_cast<unsigned long long>(f.id), f.keyframe_new_points, f.keyframe_new_dynamic,
                share(f.keyframe_new_dynamic, f.keyframe_new_points));
    out["first_keyframe"] = {{"frame", f.id}, {"points", f.keyframe_new_points}, {"dynamic", f.keyframe_new_dynamic}};
    break;
  }
  // Lifetimes of classified points (keyframe ids are global, so the
  // difference counts keyframes created in between, culled or not).
  std::vector<double> life_static, life_dynamic;
  int alive_static = 0, alive_dynamic = 0;
  for (const auto& [id, life] : counter.points()) {
    if (life.culled_at_keyframe) {
      (life.dynamic ? life_dynamic : life_static)
          .push_back(static_cast<double>(*life.culled_at_keyframe - life.first_keyframe));
    } else {
      (life.dynamic ? alive_dynamic : alive_static) += 1;
    }
  }
  auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const long seen_dynamic = static_cast<long>(life_dynamic.size()) + alive_dynamic;
  const long seen_static = static_cast<long>(life_static.size()) + alive_static;
  std::printf("  map points seen: %ld static, %ld dynamic (%.1f %%); culled: %zu static (median life %.0f keyframes), "
              "%zu dynamic (median life %.0f keyframes); alive at the end: %d static, %d dynamic\n",
              seen_static, seen_dynamic, share(seen_dynamic, seen_static + seen_dynamic), life_static.size(),
              median(life_static), life_dynamic.size(), median(life_dynamic), alive_static, alive_dynamic);
  out["map_points"] = {{"static", seen_static},
                       {"dynamic", seen_dynamic},
                       {"culled_static", life_static.size()},
                       {"culled_dynamic", life_dynamic.size()},
                       {"median_life_static", median(life_static)},
                       {"median_life_dynamic", median(life_dynamic)},
                       {"alive_static", alive_static},
                       {"alive_dynamic", alive_dynamic}};

  // Windows: drift growth next to the dynamic share of the local-map inliers.
  std::printf("  %-11s %9s %9s %9s %7s %9s\n", "frames", "drift m", "growth m", "inl dyn%", "kfs", "kf dyn%");
  const auto& frames = counter.frames();
  double last_drift = 0;
  std::vector<double> xs, ys;
  for (std::size_t s = 0; s < frames.size(); s += static_cast<std::size_t>(a.window)) {
    const std::size_t e = std::min(frames.size(), s + static_cast<std::size_t>(a.window));
    long inl = 0, dyn = 0, kfp = 0, kfd = 0;
    int kfs = 0;
    double drift = last_drift;
    for (std::size_t k = s; k < e; ++k) {
      if (frames[k].local_inliers > 0) {
        inl += frames[k].local_inliers;
        dyn += frames[k].local_dynamic_inliers;
      }
      kfs += frames[k].keyframe;
      kfp += frames[k].keyframe_new_points;
      kfd += frames[k].keyframe_new_dynamic;
      if (frames[k].drift >= 0) drift = frames[k].drift;
    }
    const double growth = drift - last_drift;
    std::printf("  %5llu-%-5llu %9.4f %9.4f %9.2f %7d %9.1f\n", static_cast<unsigned long long>(frames[s].id),
                static_cast<unsigned long long>(frames[e - 1].id), drift, growth, share(dyn, inl), kfs,
                share(kfd, kfp));
    out["windows"].push_back({{"first", frames[s].id}, {"last", frames[e - 1].id}, {"drift", drift},
                              {"inlier_dynamic_share", share(dyn, inl) / 100}, {"keyframes", kfs}});
    xs.push_back(share(dyn, inl));
    ys.push_back(std::abs(growth));
    last_drift = drift;
  }
  // Pearson correlation of |drift growth| with the dynamic inlier share over windows.
  if (xs.size() > 2) {
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < xs.size(); ++k) mx += xs[k], my += ys[k];
    mx /= xs.size(), my /= ys.size();
    double sxy = 0, sxx = 0, syy = 0;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      sxy += (xs[k] - mx) * (ys[k] - my), sxx += (xs[k] - mx) * (xs[k] - mx), syy += (ys[k] - my) * (ys[k] - my);
    }
    const double corr = sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : 0;
    std::printf("  correlation of |drift growth| with the dynamic inlier share over windows: %.2f\n", corr);
    out["correlation"] = corr;
  }
  for (const FrameRecord& f : frames) {
    out["frames"].push_back({{"id", f.id},
                             {"local_matches", f.local_matches},
                             {"local_dynamic_matches", f.local_dynamic_matches},
                             {"local_inliers", f.local_inliers},
                             {"local_dynamic_inliers", f.local_dynamic_inliers},
                             {"first_matches", f.first_matches},
                             {"first_dynamic_matches", f.first_dynamic_matches},
                             {"first_inliers", f.first_inliers},
                             {"first_dynamic_inliers", f.first_dynamic_inliers},
                             {"keyframe_new_points", f.keyframe_new_points},
                             {"keyframe_new_dynamic", f.keyframe_new_dynamic},
                             {"first_evidence", f.first_evidence},
                             {"first_fallback", f.first_fallback},
                             {"local_evidence", f.local_evidence},
                             {"local_fallback", f.local_fallback},
                             {"drift", f.drift},
                             {"est", {f.est.x(), f.est.y(), f.est.z()}},
                             {"truth", {f.truth.x(), f.truth.y(), f.truth.z()}}});
  }
  std::vector<nlohmann::json> alive;
  for (const auto& [n, d] : counter.alive()) alive.push_back({n, d});
  out["alive_per_keyframe"] = alive;
  if (!a.json.empty()) std::ofstream(a.json) << out.dump(1) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  CLI::App app("Moving points in tracking and the map (see bench/bench_dynamic_points.cpp)", "bench_dynamic_points");
  app.add_option("--config", a.config, "settings YAML")->required();
  app.add_option("--input", a.input, "a `stillslam simulate` folder (masks/, groundtruth.txt)")->required();
  app.add_option("--groundtruth", a.groundtruth, "ground truth (default: INPUT/groundtruth.txt)");
  app.add_flag("--oracle-masks", a.oracle, "segmentation on with the exact masks (default: off)");
  app.add_flag("--oracle-instances", a.oracle_instances,
               "segmentation on with the folder's instances/, one detection per instance (default: off)");
  app.add_option("--matches-csv", a.matches_csv, "write every local-map match of every frame here (CSV)");
  app.add_option("--twin", a.twin, "with --matches-csv: the same path without movers (its depth column)");
  app.add_option("--depth-factor", a.depth_factor, "the twin's depth units per metre")->capture_default_str();
  app.add_flag("--deterministic", a.deterministic, "synchronous local mapping");
  app.add_option("--max-frames", a.max_frames, "stop after N frames (0: all)")->capture_default_str();
  app.add_option("--window", a.window, "frames per drift window")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--margin", a.margin, "px around the mask that count as dynamic")->capture_default_str()->check(
      CLI::Range(0, 20));
  app.add_option("--json", a.json, "write the counts as JSON here");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dynamic_points: %s\n", e.what());
    return 1;
  }
}
