// The motion stage in the frame builder on a synthesized scene: a textured
// wall 2 m away, the camera sliding along it (2 px a frame), a "person" who is
// part of the still wall and a "box" whose texture slides over the wall. With
// exact poses, the person leaves the mask after the evidence window and its
// features are used; the box, of a class never masked, is masked once its
// motion is seen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/map/map_point.h"
#include "stillslam/segmentation/segmentation_worker.h"
#include "stillslam/tracking/frame_builder.h"
#include "stillslam/tracking/motion_stage.h"
#include "common/blurred_noise.h"

namespace stillslam {
namespace {

constexpr double kFx = 500, kDepth = 2.0;
constexpr int kShiftPx = 2;     // camera motion, image pixels per frame
constexpr int kBoxSpeedPx = 3;  // the box's own motion, pixels per frame
const cv::Rect kPerson(120, 140, 140, 220);  // in frame 0
const cv::Rect kBox(420, 200, 110, 110);     // in frame 0

cv::Rect person_at(int k) { return kPerson - cv::Point(kShiftPx * k, 0); }
cv::Rect box_at(int k, bool box_moves, int speed = kBoxSpeedPx) {
  return kBox - cv::Point(kShiftPx * k - (box_moves ? speed * k : 0), 0);
}

// A box without texture (no features to match) at its own depth in front of
// the wall, moving `speed` pixels a frame in the image (Motion.freeSpaceShare).
struct PlainBox {
  bool enabled = false;
  int speed = kBoxSpeedPx;
  float depth = 1.0f;
};

struct Scene {
  cv::Mat wall = test::blurred_noise(480, 640 + 200, 1);
  cv::Mat box = test::blurred_noise(kBox.height, kBox.width, 2);
  bool box_moves = true;
  PlainBox plain;
  cv::Mat gray(int k) const {
    cv::Mat img = wall(cv::Rect(kShiftPx * k, 0, 640, 480)).clone();
    const cv::Rect r = box_at(k, box_moves, plain.speed) & cv::Rect(0, 0, 640, 480);
    if (plain.enabled) {
      img(r).setTo(128);
    } else {
      box.copyTo(img(box_at(k, box_moves)));
    }
    return img;
  }
  cv::Mat depth(int k) const {
    cv::Mat d(480, 640, CV_32F, cv::Scalar(static_cast<float>(kDepth)));
    if (plain.enabled) d(box_at(k, box_moves, plain.speed) & cv::Rect(0, 0, 640, 480)).setTo(plain.depth);
    return d;
  }
};

// The person and the box of frame k (the frame index is the call count).
class SceneSegmenter final : public Segmenter {
 public:
  // The person is not detected in frames [hide_from, hide_to).
  SceneSegmenter(bool box_moves, int hide_from, int hide_to, int box_speed = kBoxSpeedPx)
      : box_moves_(box_moves), hide_from_(hide_from), hide_to_(hide_to), box_speed_(box_speed) {}
  std::vector<Detection> segment(const cv::Mat& bgr) override {
    const int k = calls_++;
    auto detection = [&](int class_id, const char* name, cv::Rect r) {
      Detection d;
      d.class_id = class_id;
      d.class_name = name;
      d.score = 1.f;
      d.box = r;
      d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
      d.mask(r & cv::Rect(0, 0, bgr.cols, bgr.rows)).setTo(255);
      return d;
    };
    const cv::Rect box = box_at(k, box_moves_, box_speed_);
    if (k >= hide_from_ && k < hide_to_) return {detection(-1, "box", box)};
    return {detection(0, "person", person_at(k)), detection(-1, "box", box)};
  }

 private:
  bool box_moves_;
  int hide_from_, hide_to_;
  int box_speed_;
  int calls_ = 0;
};

struct StageRun {
  std::vector<MotionFrameStats> stats;
  std::vector<double> masked_share_person, masked_share_box;  // of the region in frame.dynamic_mask()
  // Each frame's keypoints get fresh map points before the check: those it
  // flagged as seen on a person (on the person's region, elsewhere), and culled.
  std::vector<int> flagged_on_person, flagged_elsewhere, culled;
  std::vector<int> watched_features;  // the stage's own features on the unmasked box
  std::vector<int> frame_features;    // the frame's keypoints
  // With persistent points: the most frames since a point was first flagged
  // that it was matched on the person again and not culled.
  int max_flagged_age = 0;
};

// frame_features: the frames' ORB budget.
StageRun run_scene(int frames, bool box_moves, MotionOptions options, int hide_from = -1, int hide_to = -1,
                   int frame_features = OrbOptions{}.n_features, bool persistent_points = false,
                   PlainBox plain = {}, int prediction_lag = 0) {
  OrbOptions frame_orb;
  frame_orb.n_features = frame_features;
  const CameraCalibration calib = pinhole_calibration(kFx, kFx, 320, 240, 640, 480);
  const auto setup = std::make_shared<CameraSetup>(PinholeCamera(calib, 40.0), ScalePyramid(OrbOptions{}), 3.0);
  SegmentationWorker worker(std::make_unique<SceneSegmenter>(box_moves, hide_from, hide_to, plain.speed), {0}, 0);
  FrameBuilder builder(setup, SensorType::Rgbd, frame_orb, &worker);
  options.enabled = true;
  MotionStage stage(setup->camera, OrbOptions{}, {0}, 0, options);
  builder.set_motion_stage(&stage);
  Scene scene;
  scene.box_moves = box_moves;
  scene.plain = plain;
  StageRun out;
  std::vector<MapPointPtr> points;  // by keypoint index, with persistent_points
  std::map<std::uint64_t, int> first_flagged;  // by point id
  std::uint64_t next_point_id = 0;
  for (int k = 0; k < frames; ++k) {
    SensorFrame in;
    in.gray = scene.gray(k);
    cv::cvtColor(in.gray, in.color, cv::COLOR_GRAY2BGR);
    in.depth = scene.depth(k);
    in.index = static_cast<std::size_t>(k);
    in.name = "frame " + std::to_string(k);
    // Exact pose: the camera slides along +x, kShiftPx pixels a frame.
    const auto pose_of = [](int frame_index) {
      Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
      T_world_cam.translation().x() = kShiftPx * frame_index * kDepth / kFx;
      return Eigen::Isometry3d(T_world_cam.inverse());
    };
    // The predicted pose (Motion.predictedCheck): exact, or that of prediction_lag frames before.
    stage.set_prediction(pose_of(std::max(0, k - prediction_lag)));
    FrameBuildStats stats;
    Frame frame = builder.build(in, static_cast<std::uint64_t>(k), &stats);
    out.watched_features.push_back(stage.watched_features());
    out.frame_features.push_back(static_cast<int>(frame.size()));
    frame.set_pose(pose_of(k));
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (persistent_points && i < points.size() && !points[i]->is_bad()) {
        frame.set_map_point(i, points[i]);
        continue;
      }
      frame.set_map_point(i, std::make_shared<MapPoint>(next_point_id++, Eigen::Vector3d::Zero(), nullptr));
      if (persistent_points) points.resize(std::max(points.size(), i + 1)), points[i] = frame.map_point(i);
    }
    out.culled.push_back(stage.on_tracked(frame, true));
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const MapPointPtr& mp = frame.map_point(i);
      if (!mp->on_dynamic_instance() || mp->is_bad()) continue;
      if (!person_at(k).contains(cv::Point(frame.keypoints_raw()[i].pt))) continue;
      out.max_flagged_age = std::max(out.max_flagged_age, k - first_flagged.try_emplace(mp->id(), k).first->second);
    }
    int on_person = 0, elsewhere = 0;
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (!frame.map_point(i)->on_dynamic_instance()) continue;
      ++(person_at(k).contains(cv::Point(frame.keypoints_raw()[i].pt)) ? on_person : elsewhere);
    }
    out.flagged_on_person.push_back(on_person);
    out.flagged_elsewhere.push_back(elsewhere);
    out.stats.push_back(stats.motion);
    const cv::Mat1b& mask = frame.dynamic_mask();
    auto share = [&](cv::Rect r) {
      r &= cv::Rect(0, 0, 640, 480);
      return mask.empty() ? 0.0 : cv::countNonZero(mask(r)) / static_cast<double>(r.area());
    };
    out.masked_share_person.push_back(share(person_at(k)));
    out.masked_share_box.push_back(share(box_at(k, box_moves, plain.speed)));
  }
  return out;
}

TEST(MotionStage, StillPersonLeavesTheMaskMovingBoxEntersIt) {
  MotionOptions o;
  o.span = 6;
  o.person_frames = 10;
  const StageRun r = run_scene(30, true, o);
  // Class-only at first: the person masked, the box not.
  EXPECT_EQ(r.masked_share_person[0], 1.0);
  EXPECT_EQ(r.masked_share_box[0], 0.0);
  EXPECT_GT(r.stats[0].instance_features, 50);
  EXPECT_GT(r.stats[0].features_removed_by_class, 0);
  // Static after span + person_frames judged frames: from the frame after that on, unmasked.
  const int first_static = o.span + o.person_frames;
  for (int k = first_static; k < 30; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(r.masked_share_person[k], 0.0);
    EXPECT_EQ(r.stats[k].static_instances, 1);
    EXPECT_GT(r.stats[k].features_kept_by_motion, 20);
  }
  for (int k = 0; k < first_static; ++k) EXPECT_EQ(r.stats[k].features_kept_by_motion, 0) << k;
  // The points the kept person's features match are flagged (no saved map holds them), no other point is.
  for (int k = 0; k < 30; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(r.flagged_on_person[k], k < first_static ? 0 : r.stats[k].features_kept_by_motion);
    EXPECT_EQ(r.flagged_elsewhere[k], 0);
  }
  // The box moves 3 px a frame against the wall: 18 px over the span, seen at
  // the first comparison, masked from the next frame on.
  for (int k = 0; k <= o.span; ++k) EXPECT_EQ(r.masked_share_box[k], 0.0) << k;
  for (int k = o.span + 1; k < 30; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(r.masked_share_box[k], 1.0);
    EXPECT_EQ(r.stats[k].moving_instances, 1);
    EXPECT_GT(r.stats[k].features_removed_by_motion, 0);
  }
  // In the frame that finds the box moving, the points of its still tracked features are culled.
  EXPECT_EQ(r.culled[o.span - 1], 0);
  EXPECT_GT(r.culled[o.span], 5);
}

// The same map points are matched frame after frame: on the person kept as
// static they live Motion.keptPointFrames frames from the first frame they
// were matched there, then are culled (its sway must not stay in the map).
TEST(MotionStage, PointsOnAStillPersonLiveKeptPointFramesOnly) {
  MotionOptions o;
  o.span = 6;
  o.person_frames = 10;
  o.kept_point_frames = 0;
  const int first_static = o.span + o.person_frames;
  const StageRun unlimited = run_scene(40, true, o, -1, -1, OrbOptions{}.n_features, true);
  EXPECT_GE(unlimited.max_flagged_age, 10);
  for (int k = o.span + 1; k < 40; ++k) EXPECT_EQ(unlimited.culled[k], 0) << k;
  o.kept_point_frames = 4;
  const StageRun limited = run_scene(40, true, o, -1, -1, OrbOptions{}.n_features, true);
  EXPECT_EQ(limited.max_flagged_age, 3);
  for (int k = o.span + 1; k < first_static + 4; ++k) EXPECT_EQ(limited.culled[k], 0) << k;
  int culled = 0;
  for (int k = first_static + 4; k < 40; ++k) culled += limited.culled[k];
  EXPECT_GT(culled, 50);
  // The person stays kept: its features still track.
  for (int k = first_static; k < 40; ++k) EXPECT_GT(limited.stats[k].features_kept_by_motion, 20) << k;
}

// Motion.keptFeatures: the kept person's features come from a budget of
// their own, and the frame's budget goes to the rest of the view as while the
// person was masked; without it the person takes a share of the frame's.
TEST(MotionStage, AKeptPersonCanGetFeaturesOfItsOwnBudget) {
  MotionOptions o;
  o.span = 6;
  o.person_frames = 10;
  const int first_static = o.span + o.person_frames, frames = 24, budget = 400;
  const StageRun shared = run_scene(frames, false, o, -1, -1, budget);
  o.kept_features = 16;
  const StageRun own = run_scene(frames, false, o, -1, -1, budget);
  for (int k = 0; k < first_static; ++k) EXPECT_EQ(own.frame_features[k], shared.frame_features[k]) << k;
  int shared_person = 0, gained = 0;
  for (int k = first_static; k < frames; ++k) {
    SCOPED_TRACE(k);
    const int own_person = own.stats[k].features_kept_by_motion;
    EXPECT_GT(own_person, 4);
    EXPECT_LE(own_person, 16 * 3 / 2);  // extract_in_boxes may exceed its budget by half
    EXPECT_EQ(own.flagged_on_person[k], own_person);
    EXPECT_EQ(own.stats[k].features_removed_by_class, 0);  // nothing masked: the person's corners are not removed
    const int own_rest = own.frame_features[k] - own_person;
    const int shared_rest = shared.frame_features[k] - shared.stats[k].features_kept_by_motion;
    EXPECT_GT(own_rest, shared_rest);
    shared_person += shared.stats[k].features_kept_by_motion;
    gained += own_rest - shared_rest;
  }
  std::printf("kept person's features in the frame's budget: %d over %d frames; the rest of the view gains %d with "
              "its own budget\n", shared_person, frames - first_static, gained);
  EXPECT_GT(gained, shared_person / 2);
}

// The person goes undetected for 5 frames (its id is dropped after 3) and
// comes back under a new id at the same place: with places it takes over
// the old id's evidence and leaves the mask the frame after it is back;
// without (placeRadius 0) it needs person_frames agreeing frames again.
TEST(MotionStage, StillPersonBackUnderANewIdKeepsItsEvidence) {
  MotionOptions o;
  o.span = 6;
  o.person_frames = 10;
  constexpr int kHideFrom = 20, kBack = 25, kFrames = 45;
  const StageRun with = run_scene(kFrames, false, o, kHideFrom, kBack);
  for (int k = o.span + o.person_frames; k < kHideFrom; ++k) EXPECT_EQ(with.stats[k].static_instances, 1) << k;
  EXPECT_EQ(with.masked_share_person[kBack], 1.0);  // a new id: masked until its place is known
  for (int k = kBack + 1; k < kFrames; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(with.masked_share_person[k], 0.0);
    EXPECT_EQ(with.stats[k].static_instances, 1);
  }
  o.place_radius_m = 0;
  const StageRun without = run_scene(kFrames, false, o, kHideFrom, kBack);
  for (int k = kBack; k <= kBack + o.person_frames; ++k) EXPECT_EQ(without.masked_share_person[k], 1.0) << k;
}

// Motion.watchObjects: the unmasked box gets features of its own for the
// check (from the instance budget, the frame's being spread over the whole
// view); without it, none until it is masked.
TEST(MotionStage, UnmaskedObjectsGetFeaturesOfTheirOwn) {
  MotionOptions o;
  const StageRun with = run_scene(3, false, o);
  o.watch_objects = false;
  const StageRun without = run_scene(3, false, o);
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_GT(with.watched_features[k], 40);  // at least half an equal share of 200, less the box's border
    EXPECT_EQ(without.watched_features[k], 0);
    EXPECT_EQ(with.masked_share_box[k], 0.0);  // watched, not masked
  }
}

TEST(MotionStage, StillBoxStaysUnmasked) {
  const StageRun r = run_scene(20, false, MotionOptions{});
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(r.masked_share_box[k], 0.0) << k;
    EXPECT_EQ(r.stats[k].moving_instances, 0) << k;
  }
}

// A plain box (no features to match) pushed 10 px a frame at 1 m in front of
// the 2 m wall: found moving from depth (Motion.freeSpaceShare) at the first
// comparison and masked from the next frame on; with freeSpaceShare 0 never.
// The same box standing still is never masked.
TEST(MotionStage, PlainBoxFoundMovingFromDepth) {
  MotionOptions o;
  o.free_space_share = 0.3;
  PlainBox plain;
  plain.enabled = true;
  plain.speed = 10;
  const StageRun r = run_scene(20, true, o, -1, -1, OrbOptions{}.n_features, false, plain);
  for (int k = 0; k <= o.span; ++k) EXPECT_EQ(r.stats[k].moving_instances, 0) << k;
  for (int k = o.span + 1; k < 20; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(r.stats[k].moving_instances, 1);
    EXPECT_GT(r.masked_share_box[k], 0.95);
  }
  o.free_space_share = 0;
  const StageRun off = run_scene(20, true, o, -1, -1, OrbOptions{}.n_features, false, plain);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(off.stats[k].moving_instances, 0) << k;
  // Still at 1 m: it slides 4 px a frame in the image as the camera moves (2 px at the wall's 2 m).
  o.free_space_share = 0.3;
  plain.speed = -kShiftPx;
  const StageRun still = run_scene(20, true, o, -1, -1, OrbOptions{}.n_features, false, plain);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(still.stats[k].moving_instances, 0) << k;
  // Also judged the other way round (Motion.freeSpaceVacated) and against the
  // view 12 frames back (Motion.freeSpaceFrames): the pushed box is found at
  // the first comparison, the still one never.
  o.free_space_vacated = true;
  o.free_space_frames = 12;
  plain.speed = 10;
  const StageRun both = run_scene(20, true, o, -1, -1, OrbOptions{}.n_features, false, plain);
  for (int k = 0; k <= 12; ++k) EXPECT_EQ(both.stats[k].moving_instances, 0) << k;
  for (int k = 13; k < 20; ++k) EXPECT_EQ(both.stats[k].moving_instances, 1) << k;
  plain.speed = -kShiftPx;
  const StageRun both_still = run_scene(20, true, o, -1, -1, OrbOptions{}.n_features, false, plain);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(both_still.stats[k].moving_instances, 0) << k;
}

// Motion.predictedCheck: the box is judged at the frame's predicted pose
// before the frame is tracked, so the frame whose comparison finds it moving
// is masked already (without the check: from the next frame, above); the
// same for the plain box found from depth. A still box stays unmasked, also
// when the prediction is a frame behind (2 px off over the whole view).
TEST(MotionStage, AnObjectFoundMovingAtThePredictedPoseIsMaskedInItsOwnFrame) {
  MotionOptions o;
  o.span = 6;
  o.predicted_check = true;
  const StageRun r = run_scene(20, true, o);
  for (int k = 0; k < o.span; ++k) EXPECT_EQ(r.masked_share_box[k], 0.0) << k;
  EXPECT_EQ(r.masked_share_box[o.span], 1.0);
  EXPECT_EQ(r.stats[o.span].moving_instances, 1);
  EXPECT_EQ(r.stats[o.span].predicted_moving_instances, 1);
  EXPECT_GT(r.stats[o.span].features_removed_by_motion, 5);
  for (int k = o.span + 1; k < 20; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(r.masked_share_box[k], 1.0);
    EXPECT_EQ(r.stats[k].moving_instances, 1);
    EXPECT_EQ(r.stats[k].predicted_moving_instances, 0);  // masked since
  }
  // Its features were removed before tracking: none left for on_tracked() to cull.
  EXPECT_EQ(r.culled[o.span], 0);
  o.predicted_check = false;
  const StageRun off = run_scene(20, true, o);
  EXPECT_EQ(off.masked_share_box[o.span], 0.0);
  EXPECT_EQ(off.stats[o.span].predicted_moving_instances, 0);
  o.predicted_check = true;
  const StageRun lag = run_scene(20, false, o, -1, -1, OrbOptions{}.n_features, false, {}, 1);
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(lag.masked_share_box[k], 0.0) << k;
    EXPECT_EQ(lag.stats[k].moving_instances, 0) << k;
  }
  o.free_space_share = 0.3;
  PlainBox plain;
  plain.enabled = true;
  plain.speed = 10;
  const StageRun depth = run_scene(20, true, o, -1, -1, OrbOptions{}.n_features, false, plain);
  for (int k = 0; k < o.span; ++k) EXPECT_EQ(depth.stats[k].moving_instances, 0) << k;
  for (int k = o.span; k < 20; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(depth.stats[k].moving_instances, 1);
    EXPECT_GT(depth.masked_share_box[k], 0.95);
  }
  EXPECT_EQ(depth.stats[o.span].predicted_moving_instances, 1);
}

// Motion.keptFeaturesAreaFactor: the kept person's own budget is its share
// of the image's pixels times the frame's budget (times the factor), capped
// by Motion.keptFeatures.
TEST(MotionStage, AKeptPersonsOwnBudgetCanScaleWithItsArea) {
  MotionOptions o;
  o.span = 6;
  o.person_frames = 10;
  o.kept_features = 400;
  const int first_static = o.span + o.person_frames, frames = 22, budget = 400;
  const StageRun fixed = run_scene(frames, false, o, -1, -1, budget);
  o.kept_features_area_factor = 1;
  const StageRun scaled = run_scene(frames, false, o, -1, -1, budget);
  o.kept_features_area_factor = 0.5;
  const StageRun half = run_scene(frames, false, o, -1, -1, budget);
  // The person covers 140 x 220 of 640 x 480 pixels (10 %) and the stage is
  // given the default ORB settings (1000 features; System gives it the
  // frame's): about 100 features.
  const int area_budget = static_cast<int>(std::lround(OrbOptions{}.n_features * 140.0 * 220.0 / (640.0 * 480.0)));
  for (int k = first_static; k < frames; ++k) {
    SCOPED_TRACE(k);
    EXPECT_GT(fixed.stats[k].features_kept_by_motion, scaled.stats[k].features_kept_by_motion * 3 / 2);
    EXPECT_GT(scaled.stats[k].features_kept_by_motion, area_budget / 2);
    EXPECT_LE(scaled.stats[k].features_kept_by_motion, area_budget * 3 / 2);
    EXPECT_LE(half.stats[k].features_kept_by_motion, area_budget * 3 / 4);
    EXPECT_LT(half.stats[k].features_kept_by_motion, scaled.stats[k].features_kept_by_motion);
  }
}

TEST(MotionStage, OptionsOutOfRangeNameTheField) {
  MotionOptions o;
  o.span = 0;
  try {
    o.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("MotionOptions.span"), std::string::npos);
  }
}

}  // namespace
}  // namespace stillslam
