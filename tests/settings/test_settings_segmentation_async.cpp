// Segmentation.* keys of the asynchronous segmentation (issue #16).
#include <gtest/gtest.h>

#include <string>

#include "io/temp_dir.h"
#include "settings_test_files.h"
#include "stillslam/core/error.h"
#include "stillslam/settings/settings.h"

namespace stillslam {
namespace {

using test::TempDir;

const std::string& kTum = test::kRgbdSettings;  // segmentation off: the keys are read all the same

TEST(SettingsSegmentationAsync, DefaultsAndKeys) {
  TempDir dir;
  const Settings d = load_settings(dir.write("d.yaml", kTum));
  EXPECT_EQ(d.segmentation.mode, SegmentationMode::Sync);
  EXPECT_EQ(d.segmentation.interval, 5);
  EXPECT_EQ(d.segmentation.modelled_latency, 5);
  const Settings s = load_settings(dir.write(
      "a.yaml", kTum + "Segmentation.mode: async\nSegmentation.interval: 5\nSegmentation.maxMaskAge: 12\n"
                       "Segmentation.keyframeMaskAge: 4\nSegmentation.modelledLatency: 2\n"
                       "Segmentation.urgentInliers: 70\nSegmentation.maxGrowPx: 12\nSegmentation.keyframeHold: 0\n"
                       "Segmentation.threadNice: 12\n"));
  EXPECT_EQ(s.segmentation.mode, SegmentationMode::Async);
  EXPECT_EQ(s.segmentation.interval, 5);
  EXPECT_EQ(s.segmentation.max_mask_age, 12);
  EXPECT_EQ(s.segmentation.keyframe_mask_age, 4);
  EXPECT_EQ(s.segmentation.modelled_latency, 2);
  EXPECT_EQ(s.segmentation.urgent_inliers, 70);
  EXPECT_EQ(d.segmentation.max_grow_px, 30);
  EXPECT_EQ(s.segmentation.max_grow_px, 12);
  EXPECT_EQ(s.segmentation.thread_nice, 12);
  EXPECT_EQ(d.segmentation.thread_nice, 10);
  EXPECT_TRUE(d.segmentation.keyframe_hold);
  EXPECT_FALSE(s.segmentation.keyframe_hold);
  EXPECT_FALSE(d.segmentation.provisional_points);
  EXPECT_FALSE(d.segmentation.held_evidence);
  const Settings h = load_settings(dir.write("h.yaml", kTum + "Segmentation.heldEvidence: 1\n"));
  EXPECT_TRUE(h.segmentation.held_evidence);
  const Settings p = load_settings(dir.write("p.yaml", kTum + "Segmentation.provisionalPoints: 1\n"));
  EXPECT_TRUE(p.segmentation.provisional_points);
  EXPECT_FALSE(d.segmentation.start_check);
  EXPECT_FALSE(d.segmentation.keyframe_check);
  EXPECT_FALSE(d.segmentation.check_new_points);
  const Settings c = load_settings(dir.write(
      "c.yaml", kTum + "Segmentation.startCheck: 1\nSegmentation.keyframeCheck: 1\nSegmentation.checkNewPoints: 1\n"));
  EXPECT_TRUE(c.segmentation.start_check);
  EXPECT_TRUE(c.segmentation.keyframe_check);
  EXPECT_TRUE(c.segmentation.check_new_points);
  const Settings k = load_settings(dir.write("k.yaml", kTum + "Segmentation.keyframeCheck: 1\n"));
  EXPECT_FALSE(k.segmentation.start_check);
  EXPECT_TRUE(k.segmentation.keyframe_check);
  EXPECT_EQ(d.segmentation.near_person_px_per_frame, 0.0);
  EXPECT_EQ(d.segmentation.near_person_max_px, 40);
  EXPECT_EQ(d.segmentation.near_person_depth_band, 0.5);
  const Settings n = load_settings(dir.write(
      "n.yaml", kTum + "Segmentation.nearPersonPxPerFrame: 4.5\nSegmentation.nearPersonMaxPx: 25\n"
                       "Segmentation.nearPersonDepthBand: 0.3\n"));
  EXPECT_EQ(n.segmentation.near_person_px_per_frame, 4.5);
  EXPECT_EQ(n.segmentation.near_person_max_px, 25);
  EXPECT_EQ(n.segmentation.near_person_depth_band, 0.3);
  EXPECT_TRUE(d.segmentation.near_person_at_start);
  const Settings ns = load_settings(dir.write("ns.yaml", kTum + "Segmentation.nearPersonAtStart: 0\n"));
  EXPECT_FALSE(ns.segmentation.near_person_at_start);
}

TEST(SettingsSegmentationAsync, BadValuesNameTheKey) {
  TempDir dir;
  struct Case {
    std::string text, key, hint;
  };
  const std::vector<Case> cases{
      {kTum + "Segmentation.mode: fast\n", "Segmentation.mode", "sync"},
      {kTum + "Segmentation.mode: 1\n", "Segmentation.mode", "async"},
      {kTum + "Segmentation.interval: 0\n", "Segmentation.interval", "is 0: must be in [1, 1000]"},
      {kTum + "Segmentation.maxMaskAge: -1\n", "Segmentation.maxMaskAge", "is -1: must be in [0, 1000]"},
      {kTum + "Segmentation.maxGrowPx: -1\n", "Segmentation.maxGrowPx", "is -1: must be in [0, 1000]"},
      {kTum + "Segmentation.keyframeHold: 2\n", "Segmentation.keyframeHold", "must be 0 or 1"},
      {kTum + "Segmentation.provisionalPoints: 2\n", "Segmentation.provisionalPoints", "must be 0 or 1"},
      {kTum + "Segmentation.provisionalPoints: 1\nSegmentation.keyframeHold: 0\n", "Segmentation.provisionalPoints",
       "needs keyframe_hold"},
      {kTum + "Segmentation.heldEvidence: 2\n", "Segmentation.heldEvidence", "must be 0 or 1"},
      {kTum + "Segmentation.heldEvidence: 1\nSegmentation.keyframeHold: 0\n", "Segmentation.heldEvidence",
       "needs keyframe_hold"},
      {kTum + "Segmentation.heldEvidence: 1\nSegmentation.provisionalPoints: 1\n", "Segmentation.heldEvidence",
       "without provisional_points"},
      {kTum + "Segmentation.startCheck: 2\n", "Segmentation.startCheck", "must be 0 or 1"},
      {kTum + "Segmentation.keyframeCheck: -1\n", "Segmentation.keyframeCheck", "must be 0 or 1"},
      {kTum + "Segmentation.checkNewPoints: 2\n", "Segmentation.checkNewPoints", "must be 0 or 1"},
      {kTum + "Segmentation.checkNewPoints: 1\n", "Segmentation.checkNewPoints", "needs start_check or keyframe_check"},
      {kTum + "Segmentation.keyframeCheck: 1\nSegmentation.provisionalPoints: 1\n", "Segmentation.keyframeCheck",
       "cannot be combined with provisional_points"},
      {kTum + "Segmentation.startCheck: 1\nSegmentation.provisionalPoints: 1\n", "Segmentation.startCheck",
       "cannot be combined with provisional_points"},
      {kTum + "Segmentation.maxMaskAge: 2\nSegmentation.modelledLatency: 3\n", "Segmentation.modelledLatency",
       "must be at most max_mask_age"},
      {kTum + "Segmentation.nearPersonPxPerFrame: -1\n", "Segmentation.nearPersonPxPerFrame",
       "is -1: must be in [0, 100]"},
      {kTum + "Segmentation.nearPersonPxPerFrame: 101\n", "Segmentation.nearPersonPxPerFrame",
       "is 101: must be in [0, 100]"},
      {kTum + "Segmentation.nearPersonMaxPx: -1\n", "Segmentation.nearPersonMaxPx", "is -1: must be in [0, 1000]"},
      {kTum + "Segmentation.nearPersonMaxPx: 1001\n", "Segmentation.nearPersonMaxPx", "is 1001: must be in [0, 1000]"},
      {kTum + "Segmentation.nearPersonAtStart: 2\n", "Segmentation.nearPersonAtStart", "must be 0 or 1"},
      {kTum + "Segmentation.nearPersonDepthBand: 0\n", "Segmentation.nearPersonDepthBand", "is 0: must be in (0, 100]"},
      {kTum + "Segmentation.nearPersonDepthBand: 101\n", "Segmentation.nearPersonDepthBand",
       "is 101: must be in (0, 100]"},
  };
  for (const Case& c : cases) {
    const std::string message = test::settings_error(dir, c.text);
    SCOPED_TRACE(c.key);
    EXPECT_NE(message.find("'" + c.key + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(c.hint), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace stillslam
