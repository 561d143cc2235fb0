#include "stillslam/tracking/near_person.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/option_check.h"

namespace stillslam {

double NearPersonOptions::radius_px(int mask_age) const {
  return std::min(static_cast<double>(max_px), px_per_frame * std::max(mask_age, 0));
}

void NearPersonOptions::check() const {
  using namespace option_check;
  in_range("NearPersonOptions.px_per_frame", px_per_frame, 0, 100);
  in_range("NearPersonOptions.max_px", max_px, 0, 1000);
  in_half_open("NearPersonOptions.depth_band_m", depth_band_m, 0, 100);
}

std::vector<char> near_carried_person(const Frame& frame, const NearPersonOptions& options) {
  std::vector<char> near(frame.size(), 0);
  if (!options.enabled() || frame.mask_age() <= 0 || frame.carried_instances().empty()) return near;
  const double radius = options.radius_px(frame.mask_age());
  if (radius <= 0) return near;
  const int reach = static_cast<int>(std::ceil(radius)) + 1;
  for (const CarriedInstance& inst : frame.carried_instances()) {
    if (inst.mask.empty() || !(inst.depth > 0)) continue;
    const cv::Rect box = cv::boundingRect(inst.mask);
    if (box.area() == 0) continue;
    const cv::Rect image(0, 0, inst.mask.cols, inst.mask.rows);
    const cv::Rect area = cv::Rect(box.x - reach, box.y - reach, box.width + 2 * reach, box.height + 2 * reach) & image;
    // Distance of each pixel of the area to the nearest pixel of the instance.
    cv::Mat1b outside;
    cv::compare(inst.mask(area), 0, outside, cv::CMP_EQ);
    cv::Mat1f distance;
    cv::distanceTransform(outside, distance, cv::DIST_L2, cv::DIST_MASK_5);
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const float z = frame.depth(i);
      if (near[i] || !(z > 0) || std::abs(z - inst.depth) > options.depth_band_m) continue;
      const cv::Point2f& pt = frame.keypoints_raw()[i].pt;
      const cv::Point p(cvRound(pt.x) - area.x, cvRound(pt.y) - area.y);
      if (p.x < 0 || p.y < 0 || p.x >= area.width || p.y >= area.height) continue;
      if (distance(p) <= radius) near[i] = 1;
    }
  }
  return near;
}

}  // namespace stillslam
