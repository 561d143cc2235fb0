// Stable instance ids across segmentations: matched by mask overlap within a
// class, new ids for new instances, dropped after a few misses.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/segmentation/instance_ids.h"

namespace stillslam {
namespace {

constexpr int kPerson = 0, kCar = 2;

cv::Mat1b box(int x, int y, int w = 40, int h = 80) {
  cv::Mat1b m(240, 320, uchar(0));
  cv::rectangle(m, cv::Rect(x, y, w, h), 255, cv::FILLED);
  return m;
}

TEST(InstanceIds, PeopleKeepTheirIdsWhileTheyWalkAndCrossOrder) {
  InstanceIds ids;
  const auto first = ids.assign({box(20, 50), box(200, 50)}, {kPerson, kPerson});
  ASSERT_EQ(first, (std::vector<std::uint32_t>{1, 2}));
  // They walk towards each other a few pixels per segmentation; the detector lists them in any order.
  std::vector<std::uint32_t> last;
  for (int step = 1; step <= 10; ++step) {
    const int a = 20 + 6 * step, b = 200 - 6 * step;
    last = ids.assign({box(b, 50), box(a, 50)}, {kPerson, kPerson});
    ASSERT_EQ(last, (std::vector<std::uint32_t>{2, 1})) << step;
  }
  EXPECT_EQ(ids.tracked().size(), 2u);
}

TEST(InstanceIds, ClassMustMatchAndNewInstancesGetNewIds) {
  InstanceIds ids;
  ids.assign({box(20, 50)}, {kPerson});
  // A car where the person was is not the person.
  EXPECT_EQ(ids.assign({box(20, 50)}, {kCar}), (std::vector<std::uint32_t>{2}));
  // A person far from every tracked one is new.
  EXPECT_EQ(ids.assign({box(20, 50), box(250, 100)}, {kPerson, kPerson}), (std::vector<std::uint32_t>{1, 3}));
}

TEST(InstanceIds, MissedInstancesAreKeptForAFewSegmentationsThenForgotten) {
  InstanceIdOptions o;
  o.forget_after = 2;
  InstanceIds ids(o);
  ids.assign({box(20, 50)}, {kPerson});
  ids.assign({}, {});  // missed once
  ids.assign({}, {});  // twice
  EXPECT_EQ(ids.assign({box(22, 50)}, {kPerson}), (std::vector<std::uint32_t>{1}));  // found again: same id
  for (int i = 0; i < 3; ++i) ids.assign({}, {});
  EXPECT_TRUE(ids.tracked().empty());
  EXPECT_EQ(ids.assign({box(22, 50)}, {kPerson}), (std::vector<std::uint32_t>{2}));  // gone too long: new id
}

TEST(InstanceIds, MovedMasksAreMatchedWhereTheyAreNow) {
  InstanceIds ids;
  ids.assign({box(20, 50)}, {kPerson});
  // It ran 100 px between two segmentations: without the carried mask, no overlap.
  ids.move(1, box(120, 50));
  EXPECT_EQ(ids.assign({box(122, 52)}, {kPerson}), (std::vector<std::uint32_t>{1}));
  InstanceIds fresh;
  fresh.assign({box(20, 50)}, {kPerson});
  EXPECT_EQ(fresh.assign({box(122, 52)}, {kPerson}), (std::vector<std::uint32_t>{2}));
}

TEST(InstanceIds, BadInputIsAnError) {
  EXPECT_NEAR(mask_iou(box(0, 0, 10, 10), box(5, 0, 10, 10)), 50.0 / 150.0, 1e-12);
  EXPECT_EQ(mask_iou(cv::Mat1b(10, 10, uchar(0)), cv::Mat1b(10, 10, uchar(0))), 0.0);
  EXPECT_THROW(mask_iou(cv::Mat1b(10, 10), cv::Mat1b(10, 11)), Error);
  InstanceIds ids;
  EXPECT_THROW(ids.assign({box(0, 0)}, {}), Error);
  InstanceIdOptions o;
  o.min_iou = 0;
  EXPECT_THROW(o.check(), OptionError);
}

}  // namespace
}  // namespace stillslam
