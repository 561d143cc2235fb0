#pragma once
// Asynchronous segmentation (Segmentation.mode async) gives a segmented frame
// k its own mask only some frames later; frame k itself was built with an
// older mask carried to it, so keypoints on people the carried mask missed
// may have matched map points or made new ones there. When k's own mask
// arrives, the map points frame k saw inside it are culled
// (Segmentation.freshMaskCull): whatever k saw on a person is not static.
#include <opencv2/core.hpp>

#include <cstddef>
#include <map>
#include <vector>

#include "stillslam/map/frame.h"

namespace stillslam {

// Whether the raw pixel lies inside one of the instances (frame size,
// non-zero inside); pixels outside the image are on none.
bool on_any_instance(const std::vector<cv::Mat1b>& instances, const cv::Point2f& pixel);

class FreshMaskCheck {
 public:
  // After tracking a frame that went to the segmenter but was built with a
  // carried mask: keeps where (raw pixel) it saw which map point.
  void remember(std::size_t frame_index, const Frame& frame);
  bool remembers(std::size_t frame_index) const { return seen_.count(frame_index) > 0; }

  // The own segmentation of `frame_index` arrived, its dynamic instances
  // (frame size, undilated, non-zero inside): culls (MapPoint::set_bad) the
  // points that frame saw inside one, and forgets that frame and the ones
  // before it. The caller holds the map's update mutex. Returns how many
  // points were culled.
  int apply(std::size_t frame_index, const std::vector<cv::Mat1b>& instances);

  // A new map starts: the points remembered belong to the old one.
  void clear() { seen_.clear(); }

 private:
  struct Seen {
    cv::Point2f pixel;
    MapPointPtr point;
  };
  std::map<std::size_t, std::vector<Seen>> seen_;
};

}  // namespace stillslam
