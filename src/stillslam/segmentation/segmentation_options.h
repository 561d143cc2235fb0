#pragma once
#include <string>
#include <vector>

namespace stillslam {

// Segmentation.* settings.
struct SegmentationOptions {
  bool enabled = true;                        // Segmentation.enabled
  std::string model_path;                     // Segmentation.model (relative to the settings file)
  std::vector<std::string> classes{"person"}; // Segmentation.classes: COCO names or ids
  float score_threshold = 0.25f;              // Segmentation.scoreThreshold
  float nms_iou_threshold = 0.45f;            // Segmentation.nmsIouThreshold
  float mask_threshold = 0.5f;                // Segmentation.maskThreshold
  int mask_dilation = 0;                      // Segmentation.maskDilation, pixels
  int threads = 1;                            // Segmentation.threads (OpenCV DNN threads)
};

}  // namespace stillslam
