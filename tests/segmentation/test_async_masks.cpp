// Masks per frame in Segmentation.mode async: the deterministic latency model
// (the mask of frame k is usable from frame k + L on, whatever the timing),
// the wait beyond the maximum age, and no wait on ordinary frames.
#include "stillslam/segmentation/async_masks.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "segmentation/gated_segmenter.h"

namespace stillslam {
namespace {

using test::Gate;
using test::GatedSegmenter;

cv::Mat image() { return cv::Mat(40, 60, CV_8UC3, cv::Scalar::all(50)); }

std::unique_ptr<SegmentationStage> make_stage(std::shared_ptr<Gate> gate, bool threaded) {
  return std::make_unique<SegmentationStage>(
      DynamicMaskMaker(std::make_unique<GatedSegmenter>(std::move(gate)), {0}, 0, MaskHoldOptions{.frames = 0}),
      threaded);
}

AsyncMaskOptions options(int interval, int latency, int max_age) {
  AsyncMaskOptions o;
  o.interval = interval;
  o.modelled_latency = latency;
  o.max_mask_age = max_age;
  o.grow_px_per_frame = 0;  // the square stays where it was: its x names the source frame
  return o;
}

TEST(AsyncMasks, DeterministicLatencyModel) {
  auto gate = std::make_shared<Gate>();
  auto stage = make_stage(gate, false);
  AsyncMasks masks(*stage, options(2, 3, 15));
  std::vector<int> ages, sources;
  std::vector<ScheduleReason> reasons;
  for (std::size_t f = 0; f < 10; ++f) {
    const FrameMask m = masks.mask_for(image(), f);
    ages.push_back(m.age);
    sources.push_back(test::square_x(m.mask));
    reasons.push_back(m.scheduled);
    EXPECT_EQ(m.waited, f == 0) << f;  // only the first frame has nothing to carry
  }
  // Frame 0 waits for its own mask; requests every 2 frames; the mask of
  // frame k is used from frame k + 3 on.
  EXPECT_EQ(ages, (std::vector<int>{0, 1, 2, 3, 4, 3, 4, 3, 4, 3}));
  EXPECT_EQ(sources, (std::vector<int>{0, 0, 0, 0, 0, 2, 2, 4, 4, 6}));
  using R = ScheduleReason;
  EXPECT_EQ(reasons, (std::vector<R>{R::First, R::None, R::Interval, R::None, R::Interval, R::None, R::Interval,
                                     R::None, R::Interval, R::None}));
  EXPECT_EQ(gate->segmented, (std::vector<std::size_t>{0, 2, 4, 6, 8}));
}

TEST(AsyncMasks, TooOldAMaskMakesTheFrameWait) {
  auto gate = std::make_shared<Gate>();
  auto stage = make_stage(gate, false);
  AsyncMasks masks(*stage, options(2, 3, 3));
  std::vector<int> ages;
  std::vector<bool> waited;
  for (std::size_t f = 0; f < 6; ++f) {
    const FrameMask m = masks.mask_for(image(), f);
    ages.push_back(m.age);
    waited.push_back(m.waited);
  }
  // Frame 4 would carry frame 0's mask (age 4 > 3): it waits for the request
  // of its own (made by the interval rule), which is then fresh.
  EXPECT_EQ(ages, (std::vector<int>{0, 1, 2, 3, 0, 1}));
  EXPECT_EQ(waited, (std::vector<bool>{true, false, false, false, true, false}));
}

TEST(AsyncMasks, AFrameTooOldWithNoRequestInFlightSubmitsItsOwn) {
  auto gate = std::make_shared<Gate>();
  auto stage = make_stage(gate, false);
  AsyncMasks masks(*stage, options(100, 0, 2));
  EXPECT_EQ(masks.mask_for(image(), 0).age, 0);
  EXPECT_EQ(masks.mask_for(image(), 1).age, 1);
  EXPECT_EQ(masks.mask_for(image(), 2).age, 2);
  const FrameMask m = masks.mask_for(image(), 3);
  EXPECT_EQ(m.age, 0);
  EXPECT_EQ(m.scheduled, ScheduleReason::Waiting);
  EXPECT_EQ(gate->segmented, (std::vector<std::size_t>{0, 3}));
}

TEST(AsyncMasks, AgesCountProcessedFramesSoDroppedFramesDoNotMakeFramesWait) {
  auto gate = std::make_shared<Gate>();
  auto stage = make_stage(gate, false);
  AsyncMasks masks(*stage, options(2, 1, 3));
  // --realtime dropped 4 of every 5 input frames: only every fifth is processed.
  std::vector<int> ages, input_ages, sources;
  std::vector<bool> waited;
  for (std::size_t f = 0; f <= 45; f += 5) {
    const FrameMask m = masks.mask_for(image(), f);
    ages.push_back(m.age);
    input_ages.push_back(m.input_age);
    sources.push_back(test::square_x(m.mask));
    waited.push_back(m.waited);
  }
  // Requests every 2 processed frames (0, 10, 20, ...), usable one processed
  // frame later: ages 0..2, never above maxMaskAge 3, so only the first frame
  // waits. Counted in input frames (5..10) every frame would have waited.
  EXPECT_EQ(ages, (std::vector<int>{0, 1, 2, 1, 2, 1, 2, 1, 2, 1}));
  EXPECT_EQ(input_ages, (std::vector<int>{0, 5, 10, 5, 10, 5, 10, 5, 10, 5}));
  EXPECT_EQ(sources, (std::vector<int>{0, 0, 0, 10, 10, 20, 20, 30, 30, 40}));
  EXPECT_EQ(waited, (std::vector<bool>{true, false, false, false, false, false, false, false, false, false}));
  EXPECT_EQ(gate->segmented, (std::vector<std::size_t>{0, 10, 20, 30, 40}));
}

TEST(AsyncMasks, OrdinaryFramesDoNotWaitForABusySegmenter) {
  auto gate = std::make_shared<Gate>();
  auto stage = make_stage(gate, true);
  AsyncMasks masks(*stage, options(3, 0, 10));
  EXPECT_EQ(masks.mask_for(image(), 0).age, 0);  // nothing to carry yet: waits
  gate->close();
  for (std::size_t f = 1; f <= 3; ++f) masks.mask_for(image(), f);  // frame 3 goes to the stage and blocks there
  gate->wait_blocked();
  for (std::size_t f = 4; f <= 9; ++f) {
    const FrameMask m = masks.mask_for(image(), f);  // the stage is blocked: these return at once
    EXPECT_FALSE(m.waited);
    EXPECT_EQ(m.age, static_cast<int>(f));
    EXPECT_EQ(test::square_x(m.mask), 0);
  }
  EXPECT_EQ(masks.skipped(), 1u);  // frames 6 and 9 were requested meanwhile: 9 replaced 6
  gate->release();
  stage->wait_for(9);
  EXPECT_EQ(gate->segmented, (std::vector<std::size_t>{0, 3, 9}));
  const FrameMask m = masks.mask_for(image(), 10);
  EXPECT_EQ(m.age, 1);
  EXPECT_EQ(test::square_x(m.mask), 9);
  EXPECT_FALSE(gate->timed_out);
}

TEST(AsyncMasks, CarriedMaskGrowthIsCapped) {
  auto gate = std::make_shared<Gate>();
  auto stage = make_stage(gate, false);
  AsyncMaskOptions o = options(100, 0, 100);
  o.grow_px_per_frame = 4;
  o.max_grow_px = 10;
  AsyncMasks masks(*stage, o);
  // Frame 0's 10x10 square at the top-left corner, carried without a
  // propagator: it grows 4 px per input frame of age until the 10 px cap.
  std::vector<int> widths;
  for (std::size_t f : {0, 1, 2, 3, 8, 40}) widths.push_back(cv::countNonZero(masks.mask_for(image(), f).mask.row(0)));
  EXPECT_EQ(widths, (std::vector<int>{10, 14, 18, 20, 20, 20}));
}

}  // namespace
}  // namespace stillslam

namespace stillslam {
namespace {

TEST(AsyncMasks, CarriedMasksGoThroughThePropagatorWhenGivenTheGreyImage) {
  auto gate = std::make_shared<test::Gate>();
  auto stage = make_stage(gate, false);
  MaskPropagationOptions hold;
  hold.mode = 0;  // no motion: the margin alone shows the propagator was used
  hold.margin_px = 3;
  hold.margin_px_per_frame = 1;
  AsyncMasks masks(*stage, options(10, 0, 10), MaskPropagator(MaskPropagationCamera{50, 50, 30, 20}, hold), 0);
  const cv::Mat1b gray(40, 60, uchar(50));
  const FrameMask fresh = masks.mask_for(image(), 0, gray);
  EXPECT_EQ(fresh.age, 0);
  EXPECT_EQ(cv::countNonZero(fresh.mask), 100);  // the fresh 10x10 square as segmented
  // Segmented without depth: a sparse depth of it would be kept; of other frames not.
  EXPECT_TRUE(masks.wants_sparse_depth(0));
  EXPECT_FALSE(masks.wants_sparse_depth(1));
  masks.on_tracked(0, Eigen::Isometry3d::Identity(), cv::Mat1f(40, 60, 2.f));
  EXPECT_FALSE(masks.wants_sparse_depth(0));  // it has one now
  const FrameMask carried = masks.mask_for(image(), 2, gray);
  EXPECT_EQ(carried.age, 1);        // processed frames: frame 1 was never given
  EXPECT_EQ(carried.input_age, 2);  // the propagator's margin grows with input frames
  EXPECT_EQ(cv::countNonZero(carried.mask(cv::Rect(0, 0, 10, 10))), 100);
  // Grown by the margin at input age 2 (3 + 2 px): the square reaches about 14 px right and down.
  EXPECT_GT(carried.mask(0, 13), 0);
  EXPECT_EQ(carried.mask(0, 16), 0);
  EXPECT_GT(carried.mask(13, 0), 0);
}

}  // namespace
}  // namespace stillslam

namespace stillslam {
namespace {

// One "person", a 10x10 square at (20, 10), found in frame 0 only (the
// detector then loses it; MaskHold keeps it).
class FoundOnceSegmenter final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat& bgr) override { return segment_frame(bgr, 0); }
  std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t frame_index) override {
    if (frame_index != 0) return {};
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 1.f;
    d.box = cv::Rect2f(20, 10, 10, 10);
    d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
    d.mask(cv::Rect(20, 10, 10, 10)).setTo(255);
    return {d};
  }
};

// A "person" square of 40x40 at (160, 40) in a 320x120 frame, in every frame.
class SquarePersonSegmenter final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat& bgr) override { return segment_frame(bgr, 0); }
  std::vector<Detection> segment_frame(const cv::Mat& bgr, std::size_t) override {
    Detection d;
    d.class_id = 0;
    d.class_name = "person";
    d.score = 1.f;
    d.box = cv::Rect2f(160, 40, 40, 40);
    d.mask = cv::Mat1b::zeros(bgr.rows, bgr.cols);
    d.mask(cv::Rect(160, 40, 40, 40)).setTo(255);
    return {d};
  }
};

// Stereo: the segmented frame's right image reaches the propagator, which
// (MaskPropagation.stereoBlockDepth) gives the carried person the depth of
// its own disparity (1 m: 10 px at bf 10) instead of the sparse keypoint
// depths written under it after tracking (the wall's 5 m).
TEST(AsyncMasks, StereoRightImageGivesTheCarriedPersonItsDepth) {
  const cv::Size size(320, 120);
  cv::RNG rng(7);
  cv::Mat1b wall(size.height, size.width + 20), person(size.height, size.width + 20);
  rng.fill(wall, cv::RNG::UNIFORM, 0, 256);
  rng.fill(person, cv::RNG::UNIFORM, 0, 256);
  // Left: the person in x 160..199 at disparity 10, the wall elsewhere at 2.
  cv::Mat1b left(size), right(size);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const bool on_person = x >= 160 && x < 200 && y >= 40 && y < 80;
      left(y, x) = on_person ? person(y, x) : wall(y, x);
      const bool right_on_person = x + 10 >= 160 && x + 10 < 200 && y >= 40 && y < 80;
      right(y, x) = right_on_person ? person(y, x + 10) : wall(y, x + 2);
    }
  }
  cv::Mat1f sparse(size, 0.f);  // wall depths at a few pixels inside the person
  for (int y = 45; y < 80; y += 10) sparse(y, 180) = 5.f;
  const cv::Mat bgr(size, CV_8UC3, cv::Scalar::all(50));
  float depth[2] = {0, 0};
  for (bool block : {false, true}) {
    SegmentationStage stage(DynamicMaskMaker(std::make_unique<SquarePersonSegmenter>(), {0}, 0, MaskHoldOptions{.frames = 0}),
                            false);
    MaskPropagationOptions camera_only;
    camera_only.mode = 1;
    camera_only.stereo_block_depth = block;
    const MaskPropagationCamera camera{.fx = 100, .fy = 100, .cx = 160, .cy = 60, .bf = 10};
    // Every frame segmented, its mask usable one frame later: frame 1's mask
    // is carried to frame 2 from frame 1's sparse depths and right image.
    AsyncMasks masks(stage, options(1, 1, 10), MaskPropagator(camera, camera_only), 0);
    masks.mask_for(bgr, 0, left, {}, right);  // waits for its own mask (the first frame)
    masks.on_tracked(0, Eigen::Isometry3d::Identity(), sparse);
    masks.mask_for(bgr, 1, left, {}, right);
    ASSERT_TRUE(masks.wants_sparse_depth(1));
    masks.on_tracked(1, Eigen::Isometry3d::Identity(), sparse);
    const FrameMask m = masks.mask_for(bgr, 2, left, {}, right);
    ASSERT_EQ(m.source->frame_index, 1u);
    ASSERT_EQ(m.age, 1);
    ASSERT_EQ(m.instances.size(), 1u);
    depth[block] = m.instances[0].depth;
  }
  EXPECT_FLOAT_EQ(depth[0], 5.f);
  EXPECT_NEAR(depth[1], 1.f, 0.05);
}

TEST(AsyncMasks, HeldInstancesMoveWithTheCamera) {
  SegmentationStage stage(DynamicMaskMaker(std::make_unique<FoundOnceSegmenter>(), {0}, 0,
                                           MaskHoldOptions{.frames = 10, .grow_px_per_frame = 0}),
                          false);
  MaskPropagationOptions camera_only;
  camera_only.mode = 1;
  camera_only.margin_px = 0;
  camera_only.margin_px_per_frame = 0;
  AsyncMasks masks(stage, options(3, 0, 10), MaskPropagator(MaskPropagationCamera{50, 50, 30, 20}, camera_only), 0);
  const cv::Mat1b gray(40, 60, uchar(50));
  const cv::Mat1f depth(40, 60, 1.f);  // everything 1 m away
  // The camera moves 0.1 m right per frame: the scene moves 5 px left per frame.
  const auto pose = [](std::size_t f) {
    Eigen::Isometry3d T_cam_world = Eigen::Isometry3d::Identity();
    T_cam_world.translation().x() = -0.1 * static_cast<double>(f);
    return T_cam_world;
  };
  FrameMask m;
  for (std::size_t f = 0; f <= 4; ++f) {
    m = masks.mask_for(image(), f, gray, depth);
    if (f < 4) masks.on_tracked(f, pose(f));
  }
  // Frame 3 was segmented: the person is lost there and held (MaskHold).
  ASSERT_TRUE(masks.fresh());
  EXPECT_EQ(masks.fresh()->frame_index, 3u);
  ASSERT_EQ(masks.fresh()->held_instances.size(), 1u);
  EXPECT_EQ(m.input_age, 1);
  // Frame 4 carries the held square with the camera motion: 5 px left, at x 15..24.
  EXPECT_EQ(cv::countNonZero(m.mask), 100);
  EXPECT_EQ(m.mask(15, 15), 255);
  EXPECT_EQ(m.mask(15, 24), 255);
  EXPECT_EQ(m.mask(15, 26), 0);
}

}  // namespace
}  // namespace stillslam

namespace stillslam {
namespace {

// Segmentation.keyframeHold: keyframes made from frames 4 and 6 (masks
// carried) send those frames to the stage after tracking; each gets its own
// mask `latency` (3) processed frames later, and while one is awaited and the
// stage is busy the interval rule makes no request (a threaded stage would
// replace the awaited one).
TEST(AsyncMasks, SegmentLastGivesTheFrameItsOwnMaskAndIsNotReplaced) {
  auto gate = std::make_shared<test::Gate>();
  auto stage = make_stage(gate, false);
  AsyncMasks masks(*stage, options(3, 3, 15));
  std::vector<int> sources;
  std::vector<ScheduleReason> reasons;
  for (std::size_t f = 0; f < 12; ++f) {
    const FrameMask m = masks.mask_for(image(), f);
    sources.push_back(test::square_x(m.mask));
    reasons.push_back(m.scheduled);
    if (f == 3) {
      EXPECT_FALSE(masks.segment_last(image(), 3));  // the interval rule sent it already
    }
    if (f == 4 || f == 6) {
      EXPECT_TRUE(masks.segment_last(image(), f));
    }
  }
  using R = ScheduleReason;
  // Without the guard frame 7 (4 + 3) would have gone by the interval rule;
  // with it the next interval request is at 9, after frame 6's mask came.
  EXPECT_EQ(gate->segmented, (std::vector<std::size_t>{0, 3, 4, 6, 9}));
  EXPECT_EQ(sources, (std::vector<int>{0, 0, 0, 0, 0, 0, 3, 4, 4, 6, 6, 6}));
  EXPECT_EQ(reasons, (std::vector<R>{R::First, R::None, R::None, R::Interval, R::None, R::None, R::None, R::None,
                                     R::None, R::Interval, R::None, R::None}));
}

}  // namespace
}  // namespace stillslam
