#pragma once
// Which of the first keyframe's keypoints become map points once the next
// frames have checked it (tracking/initial_view_check.h, one check a frame).
// With masks: those no check rejected (found off the camera motion, or in
// the next frame's mask). Without masks a keypoint must also have been
// matched as an inlier, and it is kept when more checks confirmed it than
// found it moving: at the unmasked check's 1 px PnP bound a static keypoint
// with realistic noise falls just outside once in a few frames (requiring no
// miss at all kept 372 of 972 points of a view without people), while a
// walker the bound separates is off the motion from the second frame on.
#include <cstddef>
#include <vector>

#include "stillslam/tracking/initial_view_check.h"

namespace stillslam {

class StartVotes {
 public:
  // A new first keyframe with this many keypoints.
  void reset(std::size_t keypoints);
  // One accepted check of that keyframe against a next frame.
  void add(const InitialViewCheck& check);
  // Per keypoint: may become a map point.
  std::vector<bool> keep(bool unmasked) const;

 private:
  std::vector<int> confirmed_;  // checks that matched it as an inlier
  std::vector<int> rejected_;   // checks that left it out
};

}  // namespace stillslam
