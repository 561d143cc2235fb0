// Class filtering on a real indoor photo: COCO val2017 000000000139 (living room
// with four chairs and one person), from ../shared/images/coco128.
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "segmentation/test_data.h"
#include "stillslam/core/error.h"
#include "stillslam/segmentation/coco_classes.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/segmentation/yolo_segmenter.h"

namespace stillslam {
namespace {

const std::string kImage = std::string(STILLSLAM_SHARED_DIR) + "/images/coco128/images/val2017/000000000139.jpg";

int count_of(const std::vector<Detection>& dets, int class_id) {
  return static_cast<int>(std::count_if(dets.begin(), dets.end(), [&](const Detection& d) { return d.class_id == class_id; }));
}

TEST(ClassFilter, PersonOnlyVersusPersonAndChair) {
  if (!test::exists(kImage)) GTEST_SKIP() << "needs " << kImage << " (../shared is not part of a checkout)";
  const cv::Mat image = cv::imread(kImage);
  SegmentationOptions o;
  o.model_path = test::shipped_model();
  o.threads = 0;
  const auto dets = YoloSegmenter(o).segment(image);
  ASSERT_EQ(dets.size(), 10u);  // tv x2, chair x4, person, vase, potted plant, dining table
  EXPECT_EQ(count_of(dets, coco_class_id("person")), 1);
  EXPECT_EQ(count_of(dets, coco_class_id("chair")), 4);

  const auto person = resolve_class_ids({"person"});
  const auto person_chair = resolve_class_ids({"person", "chair"});
  EXPECT_NEAR(cv::countNonZero(dynamic_mask(dets, person, image.size(), 0)), 2783, 0.02 * 2783);
  // The four chairs (4085 + 3499 + 5946 + 2493 px) do not overlap the person.
  EXPECT_NEAR(cv::countNonZero(dynamic_mask(dets, person_chair, image.size(), 0)), 17443, 0.02 * 17443);

  // Restricting masks to the wanted classes keeps every detection but drops the other masks.
  o.classes = {"person", "chair"};
  o.masks_for_classes_only = true;
  const auto restricted = YoloSegmenter(o).segment(image);
  ASSERT_EQ(restricted.size(), dets.size());
  int masks = 0;
  for (const auto& d : restricted) masks += d.mask.empty() ? 0 : 1;
  EXPECT_EQ(masks, 5);
  EXPECT_EQ(cv::countNonZero(dynamic_mask(restricted, person_chair, image.size(), 0)),
            cv::countNonZero(dynamic_mask(dets, person_chair, image.size(), 0)));

  o.classes = {"person", "sofa"};  // COCO calls it "couch"
  EXPECT_THROW(YoloSegmenter{o}, Error);
}

}  // namespace
}  // namespace stillslam
