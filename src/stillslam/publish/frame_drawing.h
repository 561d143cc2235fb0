#pragma once
// Draws what the system saw on one frame onto a copy of its image: kept
// features (tracked or not), features the dynamic filter removed, the outline
// of the dynamic mask, each instance's outline with its class and score, and
// a line of text with the tracking state. For saved
// frames (`stillslam run --save-frames`) and report strips; a viewer may use
// it too. Colours are BGR and distinct from each other so a test or a reader
// can tell the kinds apart.
#include <opencv2/core.hpp>

#include "stillslam/publish/snapshots.h"

namespace stillslam {

struct FrameDrawingOptions {
  cv::Scalar tracked{0, 200, 0};      // kept and matched to a map point: green
  cv::Scalar untracked{0, 215, 255};  // kept, not matched: amber
  cv::Scalar removed{0, 0, 255};      // removed by the dynamic filter: red crosses
  cv::Scalar mask{255, 0, 255};       // dynamic mask and dynamic instances: magenta
  cv::Scalar static_instance{255, 255, 0};  // instances of classes not masked: cyan
  int feature_radius = 3;  // pixels
  bool text = true;        // the state line at the top
  void check() const;
};

// A BGR copy of frame.image (gray is converted) with the drawing; an empty
// Mat when the snapshot has no image.
cv::Mat draw_frame(const FrameSnapshot& frame, const FrameDrawingOptions& options = {});

}  // namespace stillslam
