#include "stillslam/segmentation/yolo_segmenter.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>

#include "segmentation/test_data.h"
#include "segmentation/tiny_onnx.h"
#include "stillslam/core/error.h"
#include "stillslam/segmentation/onnx_input_shape.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

SegmentationOptions shipped_options() {
  SegmentationOptions o;
  o.model_path = test::shipped_model();
  o.threads = 0;
  return o;
}

std::string error_of(const SegmentationOptions& o) {
  try {
    YoloSegmenter s(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("stillslam_seg_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

TEST(OnnxInputShape, ReadsShippedModelAndTinyModels) {
  EXPECT_EQ(onnx_input_shape(test::shipped_model()), (std::vector<std::int64_t>{1, 3, 384, 512}));
  TempDir dir;
  test::write_relu_onnx(dir.file("relu.onnx"), {1, 3, 64, 96});
  EXPECT_EQ(onnx_input_shape(dir.file("relu.onnx")), (std::vector<std::int64_t>{1, 3, 64, 96}));
}

TEST(YoloSegmenter, ReadsInputSizeAndClassCountFromTheModel) {
  YoloSegmenter seg(shipped_options());
  EXPECT_EQ(seg.input_size(), cv::Size(512, 384));
  EXPECT_EQ(seg.num_classes(), 80);
}

TEST(YoloSegmenter, MissingOrMalformedModelIsOneClearError) {
  TempDir dir;
  SegmentationOptions o = shipped_options();

  o.model_path = dir.file("missing.onnx");
  EXPECT_NE(error_of(o).find("missing.onnx' does not exist"), std::string::npos) << error_of(o);

  o.model_path = "";
  EXPECT_NE(error_of(o).find("no segmentation model"), std::string::npos);

  std::ofstream(dir.file("garbage.onnx"), std::ios::binary) << "this is not a protobuf \xff\xff\xff\xff\xff";
  o.model_path = dir.file("garbage.onnx");
  EXPECT_NE(error_of(o).find("garbage.onnx' is not a readable ONNX model"), std::string::npos) << error_of(o);

  // Valid ONNX, but a plain image-in image-out network: the output check rejects it.
  test::write_relu_onnx(dir.file("relu.onnx"), {1, 3, 64, 64});
  o.model_path = dir.file("relu.onnx");
  const std::string relu = error_of(o);
  EXPECT_NE(relu.find("relu.onnx' is not a YOLOv8/YOLO11-seg model"), std::string::npos) << relu;
  EXPECT_NE(relu.find("got (1x3x64x64)"), std::string::npos) << relu;

  // Input that cannot be a YOLO input.
  test::write_relu_onnx(dir.file("odd.onnx"), {1, 3, 60, 60});
  o.model_path = dir.file("odd.onnx");
  EXPECT_NE(error_of(o).find("fixed 1x3xHxW"), std::string::npos) << error_of(o);
}

TEST(YoloSegmenter, BadOptionsAndUnknownClassesAreErrors) {
  SegmentationOptions o = shipped_options();
  o.classes = {"person", "unicorn"};
  EXPECT_NE(error_of(o).find("'unicorn'"), std::string::npos);
  o = shipped_options();
  o.score_threshold = 1.5f;
  EXPECT_NE(error_of(o).find("SegmentationOptions.score_threshold"), std::string::npos);
  o = shipped_options();
  o.mask_threshold = 0.0f;
  EXPECT_NE(error_of(o).find("SegmentationOptions.mask_threshold"), std::string::npos);
}

TEST(YoloSegmenter, ImageTypes) {
  YoloSegmenter seg(shipped_options());
  EXPECT_THROW(seg.segment(cv::Mat()), Error);
  EXPECT_THROW(seg.segment(cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000))), Error);
  EXPECT_THROW(seg.segment(cv::Mat(480, 640, CV_32FC3, cv::Scalar::all(0.5))), Error);
  // A flat gray frame has nothing in it, whatever its shape.
  EXPECT_TRUE(seg.segment(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(114))).empty());
  EXPECT_TRUE(seg.segment(cv::Mat(3, 4000, CV_8UC3, cv::Scalar::all(114))).empty());
  EXPECT_TRUE(seg.segment(cv::Mat(1, 1, CV_8UC3, cv::Scalar::all(114))).empty());

  // Gray input is replicated to BGR: same people found as in the color image, near the same places.
  const cv::Mat color = cv::imread(test::bus_image());
  cv::Mat gray;
  cv::cvtColor(color, gray, cv::COLOR_BGR2GRAY);
  int persons = 0;
  for (const auto& d : seg.segment(gray)) {
    if (d.class_id != 0) continue;
    ++persons;
    EXPECT_EQ(d.mask.size(), gray.size());
  }
  EXPECT_EQ(persons, 3);
  cv::Mat bgra;
  cv::cvtColor(color, bgra, cv::COLOR_BGR2BGRA);
  const auto a = seg.segment(color);
  const auto b = seg.segment(bgra);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].box, b[i].box);
}

TEST(YoloSegmenter, MasksForClassesOnly) {
  const cv::Mat image = cv::imread(test::bus_image());
  SegmentationOptions o = shipped_options();
  o.masks_for_classes_only = true;
  o.classes = {"person"};
  YoloSegmenter persons_only(o);
  const auto dets = persons_only.segment(image);
  ASSERT_EQ(dets.size(), 5u);  // every detection is still reported...
  for (const auto& d : dets) EXPECT_EQ(d.mask.empty(), d.class_id != 0) << d.class_name;  // ...masks only for people

  o.classes = {"person", "bus"};
  YoloSegmenter person_bus(o);
  int with_mask = 0;
  for (const auto& d : person_bus.segment(image)) with_mask += d.mask.empty() ? 0 : 1;
  EXPECT_EQ(with_mask, 4);  // 3 people + bus, not the truck
}

}  // namespace
}  // namespace stillslam

namespace stillslam {
namespace {

// The published uint8 originals use DynamicQuantizeLinear, which OpenCV 4.6 cannot import.
TEST(YoloSegmenter, QuantizedOriginalIsAClearError) {
  const std::string model = test::shared_model("yolo11n-seg_uint8_480x640.onnx");
  if (!test::exists(model)) GTEST_SKIP() << "needs " << model << " (../shared is not part of a checkout)";
  SegmentationOptions o;
  o.model_path = model;
  o.threads = 0;
  try {
    YoloSegmenter s(o);
    FAIL() << "loaded a model OpenCV 4.6 cannot run";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("OpenCV DNN cannot load segmentation model"), std::string::npos) << what;
    EXPECT_NE(what.find("DynamicQuantizeLinear"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace stillslam
