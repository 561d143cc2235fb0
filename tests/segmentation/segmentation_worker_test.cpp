#include "stillslam/segmentation/segmentation_worker.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <thread>

#include "segmentation/test_data.h"
#include "stillslam/core/error.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/yolo_segmenter.h"

namespace stillslam {
namespace {

// Reports one "person" whose box encodes the frame's first pixel value, so the
// order of results can be checked; throws on a pixel value of 255 and finds
// nobody on 100.
class FakeSegmenter final : public Segmenter {
 public:
  std::vector<Detection> segment(const cv::Mat& bgr) override {
    const int v = bgr.at<cv::Vec3b>(0, 0)[0];
    if (v == 255) throw Error("fake failure");
    if (v == 100) return {};
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    Detection d;
    d.class_id = 0;
    d.box = cv::Rect2f(static_cast<float>(v), 0, 2, 2);
    return {d};
  }
};

cv::Mat frame(int value) { return cv::Mat(20, 30, CV_8UC3, cv::Scalar::all(value)); }

TEST(SegmentationWorker, ResultsInSubmissionOrderWithMasks) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {0}, 1);
  std::vector<std::future<SegmentationResult>> futures;
  for (int i = 0; i < 10; ++i) futures.push_back(worker.submit(frame(i)));
  for (int i = 0; i < 10; ++i) {
    const SegmentationResult r = futures[static_cast<std::size_t>(i)].get();
    ASSERT_EQ(r.detections.size(), 1u);
    EXPECT_EQ(r.detections[0].box.x, static_cast<float>(i));
    // Box-only detection (2x2 at the top border) dilated by 1 px: 4 + 2 below + 2 on each
    // side, minus the left side at the image border for i = 0.
    EXPECT_EQ(cv::countNonZero(r.dynamic_mask), i == 0 ? 8 : 10);
    EXPECT_DOUBLE_EQ(r.coverage, cv::countNonZero(r.dynamic_mask) / 600.0);
    EXPECT_GT(r.time_ms, 0.0);
  }
}

TEST(SegmentationWorker, HoldsAPersonTheSegmenterLost) {
  for (const int hold_frames : {0, 2}) {
    SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {0}, 0, MaskHoldOptions{.frames = hold_frames});
    std::vector<std::future<SegmentationResult>> futures;
    std::size_t index = 0;
    for (const int v : {5, 100, 100, 100}) futures.push_back(worker.submit(frame(v), index++));
    std::vector<SegmentationResult> r;
    for (auto& f : futures) r.push_back(f.get());
    EXPECT_EQ(cv::countNonZero(r[0].dynamic_mask), 4);
    EXPECT_EQ(r[0].held_coverage, 0.0);
    for (int k = 1; k <= 3; ++k) {
      EXPECT_TRUE(r[static_cast<std::size_t>(k)].detections.empty());
      const bool held = k <= hold_frames;
      EXPECT_EQ(r[static_cast<std::size_t>(k)].dynamic_mask(0, 5) != 0, held) << "frame " << k;
      EXPECT_EQ(r[static_cast<std::size_t>(k)].held_coverage > 0, held) << "frame " << k;
      EXPECT_DOUBLE_EQ(r[static_cast<std::size_t>(k)].coverage,
                       cv::countNonZero(r[static_cast<std::size_t>(k)].dynamic_mask) / 600.0);
    }
  }
}

TEST(SegmentationWorker, ErrorsReachTheFutureAndStopIsClean) {
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {0}, 0);
  auto bad = worker.submit(frame(255));
  auto good = worker.submit(frame(7));
  EXPECT_THROW(bad.get(), Error);
  EXPECT_EQ(good.get().detections.at(0).box.x, 7.0f);  // the worker survives a failed frame
  worker.stop();
  worker.stop();  // idempotent
  auto late = worker.submit(frame(1));
  EXPECT_THROW(late.get(), Error);
}

TEST(SegmentationWorker, DestructorWithQueuedFramesDoesNotHang) {
  std::vector<std::future<SegmentationResult>> futures;
  {
    SegmentationWorker worker(std::make_unique<FakeSegmenter>(), {0}, 0);
    for (int i = 0; i < 50; ++i) futures.push_back(worker.submit(frame(i)));
  }
  int done = 0;
  int stopped = 0;
  for (auto& f : futures) {
    try {
      f.get();
      ++done;
    } catch (const Error&) {
      ++stopped;
    }
  }
  EXPECT_EQ(done + stopped, 50);
}

TEST(SegmentationWorker, SameResultAsDirectSegmentation) {
  SegmentationOptions o;
  o.model_path = test::shipped_model();
  o.threads = 0;
  const cv::Mat image = cv::imread(test::bus_image());
  const auto direct = YoloSegmenter(o).segment(image);
  const cv::Mat1b direct_mask = dynamic_mask(direct, {0}, image.size(), 5);

  SegmentationWorker worker(std::make_unique<YoloSegmenter>(o), {0}, 5);
  const SegmentationResult r = worker.submit(image).get();
  ASSERT_EQ(r.detections.size(), direct.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(r.detections[i].class_id, direct[i].class_id);
    EXPECT_EQ(r.detections[i].score, direct[i].score);
    EXPECT_EQ(r.detections[i].box, direct[i].box);
    EXPECT_EQ(cv::norm(r.detections[i].mask, direct[i].mask, cv::NORM_L1), 0.0);
  }
  EXPECT_EQ(cv::norm(r.dynamic_mask, direct_mask, cv::NORM_L1), 0.0);
  // Three people, dilated by 5 px: 34.0k + 50.7k + 20.6k pixels plus their borders.
  EXPECT_NEAR(r.coverage, cv::countNonZero(direct_mask) / (810.0 * 1080.0), 1e-12);
  EXPECT_GT(r.coverage, (33990 + 50663 + 20566) / (810.0 * 1080.0));
  EXPECT_LT(r.coverage, 0.15);
}

}  // namespace
}  // namespace stillslam
