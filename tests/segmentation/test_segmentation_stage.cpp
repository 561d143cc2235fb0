// The asynchronous segmentation stage: latest-value hand-over (stale requests
// skipped and counted), results read without waiting, errors passed on.
#include "stillslam/segmentation/segmentation_stage.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "segmentation/gated_segmenter.h"
#include "stillslam/core/error.h"
#include "stillslam/core/thread_priority.h"

namespace stillslam {
namespace {

using test::Gate;
using test::GatedSegmenter;

cv::Mat image() { return cv::Mat(40, 60, CV_8UC3, cv::Scalar::all(50)); }

DynamicMaskMaker maker(std::shared_ptr<Gate> gate) {
  return DynamicMaskMaker(std::make_unique<GatedSegmenter>(std::move(gate)), {0}, 0, MaskHoldOptions{.frames = 0});
}

TEST(SegmentationStage, StaleRequestsAreSkippedAndCounted) {
  auto gate = std::make_shared<Gate>();
  gate->close();
  SegmentationStage stage(maker(gate), true);
  stage.submit(image(), 0);
  gate->wait_blocked();  // frame 0 is being segmented
  for (std::size_t f = 1; f <= 4; ++f) stage.submit(image(), f);
  EXPECT_TRUE(stage.busy());
  EXPECT_EQ(stage.latest(), nullptr);  // read without waiting
  gate->release();
  const auto result = stage.wait_for(4);
  ASSERT_NE(result, nullptr);
  EXPECT_EQ(result->frame_index, 4u);
  EXPECT_EQ(test::square_x(result->dynamic_mask), 4);
  EXPECT_EQ(stage.skipped(), 3u);  // 1, 2, 3 replaced before the stage took them
  EXPECT_EQ(stage.submitted(), 5u);
  EXPECT_EQ(gate->segmented, (std::vector<std::size_t>{0, 4}));
  EXPECT_FALSE(stage.busy());
  EXPECT_FALSE(gate->timed_out);
}

TEST(SegmentationStage, NotThreadedSegmentsAtOnceOnTheCallersThread) {
  auto gate = std::make_shared<Gate>();
  SegmentationStage stage(maker(gate), false);
  stage.submit(image(), 7);
  const auto result = stage.latest();
  ASSERT_NE(result, nullptr);
  EXPECT_EQ(result->frame_index, 7u);
  EXPECT_EQ(result->instances.size(), 1u);
  EXPECT_NEAR(result->coverage, 100.0 / (40 * 60), 1e-9);
  EXPECT_EQ(stage.skipped(), 0u);
}

class Failing final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat&) override { throw Error("model broke"); }
};

TEST(SegmentationStage, TheSegmentersErrorReachesTheReader) {
  SegmentationStage stage(DynamicMaskMaker(std::make_unique<Failing>(), {0}, 0), true);
  stage.submit(image(), 0);
  EXPECT_THROW(stage.wait_for(0), Error);
  EXPECT_THROW(stage.latest(), Error);
}

TEST(SegmentationStage, StopEndsAWaitAndLaterSubmitsFail) {
  auto gate = std::make_shared<Gate>();
  SegmentationStage stage(maker(gate), true);
  stage.stop();
  EXPECT_THROW(stage.wait_for(0), Error);
  EXPECT_THROW(stage.submit(image(), 0), Error);
}

// Records the nice value of the thread it segments on.
class NiceRecorder final : public Segmenter {
 public:
  explicit NiceRecorder(std::optional<int>* seen) : seen_(seen) {}
  std::vector<Detection> segment(const cv::Mat&) override {
    *seen_ = this_thread_nice();
    return {};
  }

 private:
  std::optional<int>* seen_;
};

#if defined(__linux__)
TEST(SegmentationStage, ThreadNiceLowersTheStageThreadOnly) {
  const int main_nice = this_thread_nice().value();
  std::optional<int> seen;
  {
    SegmentationStage stage(DynamicMaskMaker(std::make_unique<NiceRecorder>(&seen), {0}, 0), true, 7);
    stage.submit(image(), 0);
    stage.wait_for(0);
  }
  EXPECT_EQ(seen, std::min(main_nice + 7, kMaxNice));
  EXPECT_EQ(this_thread_nice(), main_nice);
  // Not threaded: segments on the caller's thread, whose priority stays.
  SegmentationStage inline_stage(DynamicMaskMaker(std::make_unique<NiceRecorder>(&seen), {0}, 0), false, 7);
  inline_stage.submit(image(), 0);
  EXPECT_EQ(seen, main_nice);
  EXPECT_EQ(this_thread_nice(), main_nice);
}
#endif

}  // namespace
}  // namespace stillslam
