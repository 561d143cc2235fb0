#include "stillslam/segmentation/coco_classes.h"

#include <gtest/gtest.h>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

TEST(CocoClasses, NamesAndIds) {
  ASSERT_EQ(coco_class_names().size(), 80u);
  EXPECT_EQ(coco_class_id("person"), 0);
  EXPECT_EQ(coco_class_id("bus"), 5);
  EXPECT_EQ(coco_class_id("chair"), 56);
  EXPECT_EQ(coco_class_id("Dining_Table"), 60);
  EXPECT_EQ(coco_class_id(" dining table "), 60);
  EXPECT_EQ(coco_class_id("79"), 79);
  EXPECT_EQ(coco_class_name(79), "toothbrush");
  EXPECT_EQ(coco_class_name(80), "class80");
}

TEST(CocoClasses, ResolveKeepsOrderAndDropsDuplicates) {
  EXPECT_EQ(resolve_class_ids({"chair", "person", "0", "56"}), (std::vector<int>{56, 0}));
}

TEST(CocoClasses, UnknownNamesThrowNamingTheValue) {
  for (const char* bad : {"unicorn", "80", "-1", "", "1.5", "person2"}) {
    try {
      coco_class_id(bad);
      FAIL() << "no error for '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("'" + std::string(bad) + "'"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(resolve_class_ids({"person", "ghost"}), Error);
}

}  // namespace
}  // namespace stillslam
