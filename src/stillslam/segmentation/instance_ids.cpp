#include "stillslam/segmentation/instance_ids.h"

#include <algorithm>
#include <tuple>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"

namespace stillslam {

void InstanceIdOptions::check() const {
  using namespace option_check;
  in_half_open("InstanceIdOptions.min_iou", min_iou, 0, 1);
  at_least("InstanceIdOptions.forget_after", forget_after, 0);
}

double mask_iou(const cv::Mat1b& a, const cv::Mat1b& b) {
  if (a.size() != b.size()) throw Error("mask_iou: masks of different sizes");
  const double inter = cv::countNonZero(a & b);
  const double uni = cv::countNonZero(a | b);
  return uni > 0 ? inter / uni : 0.0;
}

InstanceIds::InstanceIds(InstanceIdOptions options) : options_(options) { options_.check(); }

std::vector<std::uint32_t> InstanceIds::assign(const std::vector<cv::Mat1b>& masks,
                                               const std::vector<int>& class_ids) {
  if (masks.size() != class_ids.size()) throw Error("InstanceIds::assign: one class id per mask needed");
  // Every same-class pair above the overlap threshold, best first.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // iou, new index, tracked index
  for (std::size_t n = 0; n < masks.size(); ++n) {
    for (std::size_t t = 0; t < tracked_.size(); ++t) {
      if (tracked_[t].class_id != class_ids[n] || tracked_[t].mask.size() != masks[n].size()) continue;
      const double iou = mask_iou(masks[n], tracked_[t].mask);
      if (iou >= options_.min_iou) pairs.emplace_back(iou, n, t);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<std::uint32_t> ids(masks.size(), 0);
  std::vector<bool> matched(tracked_.size(), false);
  for (const auto& [iou, n, t] : pairs) {
    if (ids[n] != 0 || matched[t]) continue;
    ids[n] = tracked_[t].id;
    matched[t] = true;
  }
  std::vector<TrackedInstance> next;
  for (std::size_t t = 0; t < tracked_.size(); ++t) {
    if (matched[t]) continue;
    TrackedInstance missed = std::move(tracked_[t]);
    if (++missed.missed <= options_.forget_after) next.push_back(std::move(missed));
  }
  for (std::size_t n = 0; n < masks.size(); ++n) {
    if (ids[n] == 0) ids[n] = next_id_++;
    next.push_back({ids[n], class_ids[n], masks[n], 0});
  }
  std::sort(next.begin(), next.end(), [](const TrackedInstance& a, const TrackedInstance& b) { return a.id < b.id; });
  tracked_ = std::move(next);
  return ids;
}

void InstanceIds::move(std::uint32_t id, cv::Mat1b mask) {
  for (TrackedInstance& t : tracked_) {
    if (t.id == id) t.mask = std::move(mask);
  }
}

}  // namespace stillslam
