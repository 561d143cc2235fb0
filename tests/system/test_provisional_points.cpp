// ProvisionalPoints (tracking/provisional_points.h) and MapPoint::is_provisional:
// the new points of a keyframe made under a carried mask stay out of local BA,
// tracking's local map, fusion and culling until that frame's own mask comes;
// then those inside it are culled and the rest are ordinary points.
#include <gtest/gtest.h>

#include <algorithm>
#include <unordered_set>

#include "map/synthetic_scene.h"
#include "stillslam/map/fuse.h"
#include "stillslam/map/map.h"
#include "stillslam/mapping/keyframe_culling.h"
#include "stillslam/mapping/local_mapper.h"
#include "stillslam/mapping/local_bundle_adjustment.h"
#include "stillslam/mapping/point_culling.h"
#include "stillslam/tracking/local_map.h"
#include "stillslam/tracking/keypoint_pixels.h"
#include "stillslam/tracking/provisional_points.h"

namespace stillslam {
namespace {

std::unordered_set<const MapPoint*> in_local_ba(KeyFrame& kf) {
  std::unordered_set<const MapPoint*> out;
  for (const MapPointPtr& mp : gather_local_window(kf).points) out.insert(mp.get());
  return out;
}

// Frame 0's keyframes made a point at every keypoint; the keyframe of input
// frame 7 (carried mask) matched them at even keypoints and made provisional
// points at odd ones. A person covers the left quarter of the image.
struct ProvisionalScene {
  test::SyntheticScene scene{400};
  Map map;
  Frame f0, f1;
  KeyFramePtr kf0, kf0b, kf0c, kf;
  std::vector<MapPointPtr> old_points, new_points;
  cv::Mat1b mask;
  std::vector<bool> inside;

  ProvisionalScene() {
    f0 = scene.make_frame(0, test::pose_at(0));
    f0.set_pose(test::pose_at(0));
    kf0 = map.create_keyframe(f0);
    kf0b = map.create_keyframe(f0);
    kf0c = map.create_keyframe(f0);
    for (std::size_t i = 0; i < f0.size(); ++i) {
      MapPointPtr mp = map.create_map_point(*f0.unproject(i), kf0.get());
      for (const KeyFramePtr& k : {kf0, kf0b, kf0c}) {
        mp->add_observation(k.get(), i);
        k->set_map_point(i, mp);
      }
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(f0.setup().pyramid);
      old_points.push_back(mp);
    }
    f1 = scene.make_frame(1, test::pose_at(0));
    f1.set_pose(test::pose_at(0));
    for (std::size_t i = 0; i < f1.size(); i += 2) f1.set_map_point(i, old_points[i]);
    kf = map.create_keyframe(f1);
    new_points.resize(f1.size());
    for (std::size_t i = 0; i < f1.size(); ++i) {
      if (kf->map_point(i)) old_points[i]->add_observation(kf.get(), i);
      if (i % 2 == 0) continue;
      new_points[i] = map.create_map_point(*f1.unproject(i), kf.get());
      new_points[i]->add_observation(kf.get(), i);
      new_points[i]->compute_distinctive_descriptor();
      new_points[i]->update_normal_and_depth(f1.setup().pyramid);
      new_points[i]->set_provisional();
      kf->set_map_point(i, new_points[i]);
    }
    for (const KeyFramePtr& k : {kf0, kf0b, kf0c, kf}) k->update_connections();
    const cv::Size size(f1.setup().camera.width(), f1.setup().camera.height());
    mask = cv::Mat1b::zeros(size);
    mask(cv::Rect(0, 0, size.width / 4, size.height)).setTo(255);
    for (const cv::KeyPoint& k : f1.keypoints_raw()) {
      inside.push_back(mask(cv::Point(cvRound(k.pt.x), cvRound(k.pt.y))) != 0);
    }
  }
  int count(bool odd, bool in) const {
    int n = 0;
    for (std::size_t i = 0; i < inside.size(); ++i) n += (i % 2 == 1) == odd && inside[i] == in;
    return n;
  }
};

TEST(ProvisionalPoints, APointInsideItsMaskNeverReachesBundleAdjustment) {
  ProvisionalScene s;
  const int new_in = s.count(true, true), new_out = s.count(true, false), old_in = s.count(false, true);
  ASSERT_GT(new_in, 10);
  ASSERT_GT(new_out, 10);
  ASSERT_GT(old_in, 10);

  // While provisional: not in local BA, not in tracking's local map, not fused, not culled.
  std::unordered_set<const MapPoint*> ba = in_local_ba(*s.kf);
  const LocalMap local = build_local_map(s.f0, s.kf.get(), 10);
  for (std::size_t i = 1; i < s.new_points.size(); i += 2) {
    EXPECT_FALSE(ba.count(s.new_points[i].get())) << i;
    EXPECT_EQ(std::count(local.points.begin(), local.points.end(), s.new_points[i]), 0) << i;
  }
  EXPECT_EQ(ba.size(), s.old_points.size());  // the old points are all there
  const KeyFramePtr empty = s.map.create_keyframe(s.f0);  // no points yet: fusion fills it
  std::vector<MapPointPtr> provisional;
  for (const MapPointPtr& mp : s.new_points) {
    if (mp) provisional.push_back(mp);
  }
  EXPECT_EQ(fuse(*empty, provisional), 0);
  EXPECT_GT(fuse(*empty, s.old_points), 0);  // the same projection fuses ordinary points
  std::vector<MapPointPtr> recent = provisional;
  EXPECT_EQ(cull_recent_points(recent, s.kf->id() + 10, {}), 0);
  EXPECT_EQ(recent.size(), provisional.size());
  // Its keyframe is not redundant for them: they are seen by it alone (its
  // matches to frame 0's points, seen by three other keyframes, are).
  int close = 0, matched = 0;
  for (std::size_t i = 0; i < s.kf->size(); ++i) {
    if (s.kf->depth(i) < 0 || s.kf->depth(i) > s.kf->setup().close_depth) continue;
    ++close;
    matched += i % 2 == 0;
  }
  ASSERT_GT(close, 20);
  EXPECT_NEAR(keyframe_redundancy(*s.kf), static_cast<double>(matched) / close, 1e-9);

  ProvisionalPoints pending;
  pending.add(s.kf, keypoint_pixels(s.f1));
  EXPECT_EQ(pending.check(7, {s.mask}, 50).culled, 0);  // its input frame not known yet
  EXPECT_EQ(pending.assign(7), 1);
  EXPECT_EQ(pending.assign(8), 0);  // assigned once
  ProvisionalCheck c = pending.check(6, {s.mask}, 50);  // an older frame's mask: nothing happens
  EXPECT_EQ(c.culled + c.confirmed + c.unlinked, 0);
  EXPECT_FALSE(pending.empty());
  // Local BA moved the keyframe 5 cm meanwhile (not its provisional points).
  Eigen::Isometry3d moved = s.kf->T_cam_world();
  moved.translation().x() += 0.05;
  s.kf->set_pose(moved);
  c = pending.check(7, {s.mask}, 50);
  EXPECT_EQ(c.culled, new_in);
  EXPECT_EQ(c.confirmed, new_out);
  EXPECT_EQ(c.unlinked, old_in);
  EXPECT_EQ(c.unchecked, 0);
  ASSERT_EQ(c.settled.size(), 1u);  // to be fused by the caller
  EXPECT_EQ(c.settled[0], s.kf);
  EXPECT_TRUE(pending.empty());

  // After the mask: inside culled (never in BA), outside ordinary and in the next local BA.
  ba = in_local_ba(*s.kf);
  for (std::size_t i = 1; i < s.new_points.size(); i += 2) {
    const MapPointPtr& mp = s.new_points[i];
    EXPECT_EQ(mp->is_bad(), bool(s.inside[i])) << i;
    EXPECT_EQ(mp->is_provisional(), bool(s.inside[i])) << i;  // a culled one is left as it was
    EXPECT_EQ(ba.count(mp.get()) == 1, !s.inside[i]) << i;
    if (!s.inside[i]) {  // placed again from the keyframe's pose now
      EXPECT_LT((mp->position() - *s.kf->unproject(i)).norm(), 1e-9) << i;
      EXPECT_GT((mp->position() - *s.f1.unproject(i)).norm(), 0.04) << i;
    }
  }
  for (std::size_t i = 0; i < s.old_points.size(); i += 2) {
    EXPECT_EQ(s.old_points[i]->is_observed_by(s.kf.get()), !s.inside[i]) << i;
  }
  // Culling counts a confirmed point's age from its confirmation (next keyframe id 50).
  recent = provisional;
  EXPECT_EQ(cull_recent_points(recent, 51, {}), 0);
  EXPECT_EQ(cull_recent_points(recent, 52, {}), new_out);  // seen by one keyframe only
}

TEST(ProvisionalPoints, ANewerMaskOrTheEndConfirmsUnchecked) {
  ProvisionalScene s;
  ProvisionalPoints pending;
  pending.add(s.kf, keypoint_pixels(s.f1));
  EXPECT_EQ(pending.assign(5), 1);
  pending.add(s.kf, keypoint_pixels(s.f1));
  EXPECT_EQ(pending.assign(9), 1);
  // Frame 5's own mask never came (a threaded stage skipped it); frame 8's did.
  const ProvisionalCheck c = pending.check(8, {s.mask}, 20);
  EXPECT_EQ(c.unchecked, 1);
  EXPECT_EQ(c.culled, 0);
  EXPECT_EQ(c.unlinked, 0);
  EXPECT_EQ(c.confirmed, s.count(true, true) + s.count(true, false));
  EXPECT_EQ(pending.size(), 1u);
  for (std::size_t i = 1; i < s.new_points.size(); i += 2) EXPECT_FALSE(s.new_points[i]->is_provisional());
  EXPECT_EQ(pending.confirm_all(20).unchecked, 1);
  EXPECT_TRUE(pending.empty());
}

TEST(ProvisionalPoints, LocalMappingFusesTheConfirmedPoints) {
  // Frame 0's keyframes see the same places at the same keypoints as the
  // confirmed points: local mapping merges each such pair, and nothing before
  // its queue runs.
  ProvisionalScene s;
  ProvisionalPoints pending;
  pending.add(s.kf, keypoint_pixels(s.f1));
  EXPECT_EQ(pending.assign(7), 1);
  const ProvisionalCheck c = pending.check(7, {cv::Mat1b::zeros(s.mask.size())}, 50);
  const int odd = s.count(true, true) + s.count(true, false);
  ASSERT_EQ(c.confirmed, odd);
  ASSERT_EQ(c.settled.size(), 1u);
  LocalMapperOptions options;
  options.threaded = false;
  LocalMapper mapper(s.map, options);
  mapper.fuse_confirmed(c.settled[0]);
  auto fused = [&s] {
    int n = 0;
    for (std::size_t i = 1; i < s.new_points.size(); i += 2) n += s.new_points[i]->is_bad();
    return n;
  };
  EXPECT_EQ(fused(), 0);
  mapper.process_pending();
  EXPECT_GT(fused(), odd * 3 / 4);
  // Each fused keypoint of the keyframe now holds frame 0's point.
  for (std::size_t i = 1; i < s.new_points.size(); i += 2) {
    if (s.new_points[i]->is_bad()) {
      EXPECT_EQ(s.kf->map_point(i), s.old_points[i]) << i;
    }
  }
  const LocalMapperStats stats = mapper.stats();
  EXPECT_EQ(stats.keyframes, 0);  // fusion alone: no keyframe processed, no BA
  EXPECT_EQ(stats.bundle_adjustments, 0);
}

}  // namespace
}  // namespace stillslam
