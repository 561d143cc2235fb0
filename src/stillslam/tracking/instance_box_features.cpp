#include "stillslam/tracking/instance_box_features.h"

#include <algorithm>
#include <cmath>

#include "stillslam/features/brief_pattern.h"
#include "stillslam/features/orb_extractor.h"

namespace stillslam {

namespace {

// A level narrower than this keeps no corner once the patch border is off
// both sides (the extractor keeps corners BriefPattern::kRadius + 1 inside).
constexpr int kMinLevelSide = 3 * (BriefPattern::kRadius + 1);

int levels_for(cv::Size box, const OrbOptions& orb) {
  int levels = 1;
  while (levels < orb.n_levels &&
         std::min(box.width, box.height) / std::pow(orb.scale_factor, levels) >= kMinLevelSide) {
    ++levels;
  }
  return levels;
}

}  // namespace

std::vector<cv::Rect> merge_instance_boxes(const std::vector<cv::Rect>& boxes, int pad, cv::Size image) {
  const cv::Rect frame(0, 0, image.width, image.height);
  std::vector<cv::Rect> out;
  for (const cv::Rect& b : boxes) {
    const cv::Rect grown = cv::Rect(b.x - pad, b.y - pad, b.width + 2 * pad, b.height + 2 * pad) & frame;
    if (!grown.empty()) out.push_back(grown);
  }
  // Merge until no two overlap (a merged box can reach a third one).
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < out.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < out.size(); ++j) {
        if ((out[i] & out[j]).empty()) continue;
        out[i] |= out[j];
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(j));
        merged = true;
        break;
      }
    }
  }
  return out;
}

OrbFeatures extract_in_boxes(const OrbOptions& orb, int budget, const cv::Mat& gray, const cv::Mat1b& inside,
                             const std::vector<cv::Rect>& boxes) {
  OrbFeatures out;
  out.descriptors.create(0, 32, CV_8UC1);
  double total_area = 0;
  for (const cv::Rect& b : boxes) total_area += b.area();
  if (total_area <= 0 || budget <= 0) return out;
  for (const cv::Rect& box : boxes) {
    OrbOptions options = orb;
    // By area, but at least half an equal share: a small object next to a
    // large person still gets enough features to be judged.
    const double share = std::max(box.area() / total_area, 0.5 / static_cast<double>(boxes.size()));
    options.n_features = std::max(1, static_cast<int>(std::lround(budget * share)));
    options.n_levels = levels_for(box.size(), orb);
    const OrbExtractor extractor(options);
    const cv::Mat1b outside = inside(box) == 0;
    OrbFeatures f = extractor.extract(gray(box), outside, nullptr);
    for (cv::KeyPoint kp : f.keypoints) {
      kp.pt.x += static_cast<float>(box.x);
      kp.pt.y += static_cast<float>(box.y);
      out.keypoints.push_back(kp);
    }
    if (!f.descriptors.empty()) out.descriptors.push_back(f.descriptors);
  }
  return out;
}

}  // namespace stillslam
