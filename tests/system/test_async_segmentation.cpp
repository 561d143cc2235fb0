// Segmentation.mode async through the whole system on a short generated
// sequence, deterministic: the stats fields (mask age, fresh or carried,
// requests, skips) per frame and in stats.json, no keyframe from a frame with
// a mask older than the bound, and bit-for-bit repeatable runs. With
// Segmentation.keyframeHold: such keyframes are made, held and checked.
#include <gtest/gtest.h>

#include "stillslam/system/realtime_summary.h"
#include "stillslam/system/run_result_json.h"
#include "stillslam/system/system.h"
#include "system/corner_person.h"
#include "system/sim_sequence.h"

namespace stillslam {
namespace {

const test::SimSequence& sequence() {
  static const test::SimSequence seq = test::render_sim_sequence("walking_xyz", 60, 320, 240, false);
  return seq;
}

// One "person" that jumps: a 40x40 square 8 px further right in every frame,
// so a carried mask misses where the frame's own mask is.
class JumpingPerson final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat& bgr) override { return segment_frame(bgr, 0); }
  std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t frame_index) override {
    const int x = static_cast<int>(8 * frame_index) % (bgr.cols - 40);
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 1.f;
    d.box = cv::Rect2f(static_cast<float>(x), 100, 40, 40);
    d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
    d.mask(cv::Rect(x, 100, 40, 40)).setTo(255);
    return {d};
  }
};

RunResult run_async(const test::SimSequence& seq, bool keyframe_hold = false, bool provisional_points = false,
                    bool keyframe_check = false, bool check_new_points = false) {
  Settings settings = seq.settings;
  settings.segmentation.keyframe_check = keyframe_check;
  settings.segmentation.check_new_points = check_new_points;
  settings.tracking.init_min_keypoints = 300;
  settings.segmentation.enabled = true;
  settings.segmentation.mode = SegmentationMode::Async;
  settings.segmentation.interval = 4;
  settings.segmentation.modelled_latency = 2;
  settings.segmentation.keyframe_mask_age = 2;
  settings.segmentation.max_mask_age = 8;
  settings.segmentation.fresh_mask_cull = !keyframe_hold;  // its path repeats bit for bit too
  settings.segmentation.keyframe_hold = keyframe_hold;
  settings.segmentation.provisional_points = provisional_points;
  SystemOptions options;
  options.deterministic = true;
  options.segmenter_factory = [keyframe_hold]() -> std::unique_ptr<Segmenter> {
    if (keyframe_hold) return std::make_unique<JumpingPerson>();
    return std::make_unique<test::CornerPerson>();
  };
  System system(settings, SensorType::Rgbd, seq.stereo, options);
  RunResult out;
  for (const SensorFrame& f : seq.frames) {
    FrameStats stats = system.process(f);
    mark_start_frames_posed(out.frames, stats);  // the frames the map's start waited on
    out.frames.push_back(std::move(stats));
  }
  system.shutdown();
  collect_system_results(system, out);
  return out;
}

TEST(AsyncSegmentation, StatsFieldsPerFrameAndInStatsJson) {
  const RunResult r = run_async(sequence());
  ASSERT_EQ(r.frames.size(), sequence().frames.size());
  std::size_t fresh = 0, carried = 0, requests = 0, deferred = 0, keyframes = 0;
  for (const FrameStats& f : r.frames) {
    EXPECT_GE(f.build.mask_age, 0);
    EXPECT_LE(f.build.mask_age, 8);
    fresh += f.build.mask_age == 0;
    carried += f.build.mask_age > 0;
    requests += f.build.segmentation_request != ScheduleReason::None;
    deferred += f.keyframe_deferred;
    keyframes += f.keyframe;
    // The map's first keyframe included.
    if (f.keyframe) {
      EXPECT_LE(f.build.mask_age, 2) << "keyframe from an old mask, frame " << f.index;
    }
    EXPECT_EQ(f.build.segmentation_skips, 0u);  // deterministic: nothing is skipped
  }
  EXPECT_EQ(r.frames[0].build.mask_age, 0);
  EXPECT_TRUE(r.frames[0].build.mask_waited);
  EXPECT_GT(carried, fresh);
  EXPECT_GE(requests, sequence().frames.size() / 4);
  EXPECT_GE(keyframes, 2u);
  EXPECT_GT(r.trajectory.size(), sequence().frames.size() * 9 / 10);

  const nlohmann::json stats = run_result_json(r, {});
  const nlohmann::json& frames = stats["frames"];
  ASSERT_EQ(frames.size(), r.frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i]["mask_age"].get<int>(), r.frames[i].build.mask_age);
    EXPECT_EQ(frames[i]["mask_fresh"].get<bool>(), r.frames[i].build.mask_age == 0);
    EXPECT_EQ(frames[i]["segmentation_request"].get<std::string>(),
              to_string(r.frames[i].build.segmentation_request));
    EXPECT_EQ(frames[i]["keyframe_deferred"].get<bool>(), r.frames[i].keyframe_deferred);
    EXPECT_EQ(frames[i]["fresh_mask_culled"].get<int>(), r.frames[i].fresh_mask_culled);
    EXPECT_TRUE(frames[i]["times_ms"].contains("propagation_cpu"));
    EXPECT_EQ(frames[i]["times_ms"]["core_wait"].get<double>(), r.frames[i].core_wait_ms);
    EXPECT_GE(r.frames[i].core_wait_ms, 0.0);
    EXPECT_LE(r.frames[i].core_wait_ms, r.frames[i].total_ms + 1.0);  // a part of the frame's wall time
    EXPECT_TRUE(frames[i]["times_ms"].contains("latency"));
  }
  const nlohmann::json& masks = stats["summary"]["realtime"]["masks"];
  EXPECT_EQ(masks["fresh"].get<std::size_t>(), fresh);
  EXPECT_EQ(masks["carried"].get<std::size_t>(), carried);
  EXPECT_EQ(masks["segmentation_requests"].get<std::size_t>(), requests);
  EXPECT_EQ(masks["keyframes_deferred"].get<std::size_t>(), deferred);
  EXPECT_EQ(masks["segmentation_skips"].get<std::size_t>(), 0u);
  EXPECT_TRUE(stats["summary"]["realtime"].contains("fps"));
  EXPECT_TRUE(stats["summary"]["realtime"]["latency_ms"].contains("p95"));
  EXPECT_TRUE(stats["summary"]["realtime"].contains("cpu_ms_per_frame"));
}

TEST(AsyncSegmentation, DeterministicRunsRepeatBitForBit) {
  const RunResult a = run_async(sequence());
  const RunResult b = run_async(sequence());
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    EXPECT_EQ(a.frames[i].build.mask_age, b.frames[i].build.mask_age) << i;
    EXPECT_EQ(a.frames[i].keyframe, b.frames[i].keyframe) << i;
  }
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_TRUE(a.trajectory[i].T_world_cam.matrix() == b.trajectory[i].T_world_cam.matrix()) << i;
  }
}

// Counts a run's keyframes, those checked against their own frame's mask
// (held or with provisional points) and the points that check removed; every
// checked keyframe's frame had an old mask and asked for a segmentation.
struct CheckedKeyframes {
  std::size_t checked = 0, keyframes = 0;
  int removed = 0;
};

CheckedKeyframes count_checked_keyframes(const RunResult& r) {
  CheckedKeyframes c;
  for (const FrameStats& f : r.frames) {
    EXPECT_FALSE(f.keyframe_deferred) << f.index;
    c.keyframes += f.keyframe;
    c.removed += f.held_points_removed;
    if (!f.keyframe_held) continue;
    ++c.checked;
    EXPECT_TRUE(f.keyframe) << f.index;
    EXPECT_GT(f.build.mask_age, 2) << f.index;
    EXPECT_NE(f.build.segmentation_request, ScheduleReason::None) << f.index;
  }
  return c;
}

// Keyframes due on frames with masks older than keyframeMaskAge (2) are made
// and held instead of deferred; each such frame goes to the segmenter, and
// when its own mask comes the held keyframe's points inside it go.
TEST(AsyncSegmentation, KeyframeHoldMakesTheKeyframesAndChecksThemWithTheirOwnMasks) {
  const RunResult r = run_async(sequence(), true);
  const CheckedKeyframes c = count_checked_keyframes(r);
  const std::size_t held = c.checked, keyframes = c.keyframes;
  const int removed = c.removed;
  EXPECT_GE(held, 2u);
  EXPECT_GT(removed, 0);  // the jumping square covered keypoints of held keyframes
  EXPECT_GT(r.trajectory.size(), sequence().frames.size() * 9 / 10);
  // Every keyframe reached local mapping (the last ones at shutdown; the map's
  // first keyframe may be of an earlier frame than the one that started it).
  EXPECT_GE(static_cast<std::size_t>(r.mapper.keyframes), keyframes);
  EXPECT_LE(static_cast<std::size_t>(r.mapper.keyframes), keyframes + 1);
  const nlohmann::json stats = run_result_json(r, {});
  EXPECT_EQ(stats["summary"]["realtime"]["masks"]["keyframes_held"].get<std::size_t>(), held);
  EXPECT_EQ(stats["frames"][0]["keyframe_held"].get<bool>(), r.frames[0].keyframe_held);
}

TEST(AsyncSegmentation, ProvisionalPointsPassEveryKeyframeAtOnceAndCullInsideTheirOwnMasks) {
  const RunResult hold = run_async(sequence(), true);
  const RunResult r = run_async(sequence(), true, true);
  const CheckedKeyframes c = count_checked_keyframes(r);
  const std::size_t checked = c.checked, keyframes = c.keyframes;
  const int removed = c.removed;
  EXPECT_GE(checked, 2u);
  EXPECT_GT(removed, 0);  // the jumping square covered provisional points
  EXPECT_GT(r.trajectory.size(), sequence().frames.size() * 9 / 10);
  EXPECT_GE(static_cast<std::size_t>(r.mapper.keyframes), keyframes);
  EXPECT_LE(static_cast<std::size_t>(r.mapper.keyframes), keyframes + 1);
  // Not the keyframe hold's run: its keyframes waited for local mapping, these did not.
  bool differs = hold.frames.size() != r.frames.size();
  for (std::size_t i = 0; !differs && i < r.frames.size(); ++i) {
    differs = hold.frames[i].inliers != r.frames[i].inliers;
  }
  EXPECT_TRUE(differs);
}

// Segmentation.keyframeCheck with the hold (keyframeMaskAge 2): keyframes at
// mask age 1-2 go to local mapping at once and are checked when their own
// masks come (those above 2 are held as before).
TEST(AsyncSegmentation, KeyframeCheckPassesKeyframesAtOnceAndChecksThemWithTheirOwnMasks) {
  const RunResult hold = run_async(sequence(), true);
  const RunResult r = run_async(sequence(), true, false, true);
  std::size_t checked = 0, held = 0, keyframes = 0;
  int removed = 0, hold_removed = 0;
  for (const FrameStats& f : r.frames) {
    keyframes += f.keyframe;
    removed += f.held_points_removed;
    if (!f.keyframe_held) continue;
    EXPECT_TRUE(f.keyframe) << f.index;
    EXPECT_GT(f.build.mask_age, 0) << f.index;
    EXPECT_NE(f.build.segmentation_request, ScheduleReason::None) << f.index;
    (f.build.mask_age > 2 ? held : checked)++;
  }
  for (const FrameStats& f : hold.frames) hold_removed += f.held_points_removed;
  EXPECT_GE(checked, 2u);  // keyframes the hold alone passes unchecked
  EXPECT_GT(removed, 0);
  EXPECT_GT(hold_removed, 0);
  // Not the hold's run: the checked keyframes' points inside their masks went.
  bool differs = hold.frames.size() != r.frames.size();
  for (std::size_t i = 0; !differs && i < r.frames.size(); ++i) {
    differs = hold.frames[i].inliers != r.frames[i].inliers ||
              hold.frames[i].held_points_removed != r.frames[i].held_points_removed;
  }
  EXPECT_TRUE(differs);
  EXPECT_GT(r.trajectory.size(), sequence().frames.size() * 9 / 10);
  EXPECT_GE(static_cast<std::size_t>(r.mapper.keyframes), keyframes);
  EXPECT_LE(static_cast<std::size_t>(r.mapper.keyframes), keyframes + 1);
  // Culling the points made after a checked keyframe too: a run that still removes points.
  const RunResult n = run_async(sequence(), true, false, true, true);
  int new_removed = 0;
  for (const FrameStats& f : n.frames) new_removed += f.held_points_removed;
  EXPECT_GT(new_removed, 0);
}

}  // namespace
}  // namespace stillslam
