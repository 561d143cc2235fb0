#pragma once
#include <opencv2/dnn.hpp>

#include <string>
#include <vector>

#include "stillslam/segmentation/letterbox.h"
#include "stillslam/segmentation/segmentation_options.h"
#include "stillslam/segmentation/segmenter.h"

namespace stillslam {

// YOLOv8-seg / YOLO11-seg (Ultralytics export layout) on OpenCV DNN.
// The network input size is read from the ONNX graph; the frame is letterboxed
// into it, and boxes and masks come back in frame pixels.
class YoloSegmenter final : public Segmenter {
 public:
  // Loads options.model_path and runs one dummy forward to validate the output
  // layout. Throws stillslam::Error for a missing or unreadable model, a model
  // whose outputs are not (1, 4+classes+32, N) and (1, 32, H/4, W/4), or unknown
  // class names in options.classes (used by masks_for_classes_only).
  explicit YoloSegmenter(const SegmentationOptions& options);

  // Detections above options.score_threshold after NMS, highest score first; boxes
  // clipped to the frame; masks frame-size (empty for classes outside options.classes
  // when masks_for_classes_only). Not thread-safe: one segmenter per thread.
  std::vector<Detection> segment(const cv::Mat& bgr) override;

  cv::Size input_size() const { return input_size_; }  // network input (width, height)
  int num_classes() const { return num_classes_; }
  int num_mask_coefficients() const { return 32; }

 private:
  struct Outputs {
    cv::Mat predictions;  // N x (4 + classes + 32), one row per anchor
    cv::Mat protos;       // 32 x (H/4 * W/4)
    cv::Size proto_size;  // (W/4, H/4)
  };
  Outputs forward(const cv::Mat& bgr_input);
  Outputs check_outputs(std::vector<cv::Mat>& outs);
  cv::Mat1b instance_mask(const Outputs& outs, int row, const Letterbox& lb, const cv::Rect2f& box,
                          cv::Size frame_size) const;

  SegmentationOptions options_;
  cv::dnn::Net net_;
  std::vector<std::string> output_names_;
  cv::Size input_size_;
  int num_classes_ = 0;
  std::vector<bool> mask_class_;  // per class id: compute its mask
};

}  // namespace stillslam
