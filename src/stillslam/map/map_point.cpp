#include "stillslam/map/map_point.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "stillslam/features/descriptor.h"
#include "stillslam/features/scale_pyramid.h"
#include "stillslam/map/keyframe.h"

namespace stillslam {

MapPoint::MapPoint(std::uint64_t id, const Eigen::Vector3d& position_world, KeyFrame* reference)
    : id_(id),
      first_keyframe_id_(reference ? reference->id() : 0),
      culling_start_keyframe_id_(first_keyframe_id_),
      position_(position_world),
      reference_(reference) {}

int MapPoint::predict_level(double distance, const ScalePyramid& pyramid) const {
  return predict_scale_level(max_distance_, distance, pyramid);
}

int predict_scale_level(double reference_distance, double distance, const ScalePyramid& pyramid) {
  const double ratio = reference_distance / std::max(distance, 1e-9);
  int level = static_cast<int>(std::ceil(std::log(ratio) / std::log(pyramid.scale_factor)));
  return std::clamp(level, 0, pyramid.n_levels - 1);
}

std::ptrdiff_t MapPoint::index_in(const KeyFrame* kf) const {
  const auto it = observations_.find(kf);
  return it == observations_.end() ? -1 : static_cast<std::ptrdiff_t>(it->second);
}

void MapPoint::add_observation(KeyFrame* kf, std::size_t index) {
  if (!observations_.emplace(kf, index).second) return;
  num_observations_ += kf->u_right(index) >= 0 ? 2 : 1;
  descriptor_from_ = -1;
}

void MapPoint::erase_observation(KeyFrame* kf) {
  const auto it = observations_.find(kf);
  if (it == observations_.end()) return;
  num_observations_ -= kf->u_right(it->second) >= 0 ? 2 : 1;
  observations_.erase(it);
  descriptor_from_ = -1;
  if (reference_ == kf) reference_ = observations_.empty() ? nullptr : observations_.begin()->first;
  if (num_observations_ <= 2) set_bad();
}

void MapPoint::compute_distinctive_descriptor() {
  // Per-thread buffers: mapping calls this for every point of every new
  // keyframe, and fresh vectors each time were a measurable share of it.
  thread_local std::vector<const std::uint8_t*> descriptors;
  thread_local std::vector<int> distances;
  thread_local std::vector<int> row;
  descriptors.clear();
  for (const auto& [kf, idx] : observations_) {
    if (!kf->is_bad()) descriptors.push_back(kf->descriptor(idx));
  }
  if (descriptors.empty()) return;
  if (descriptor_from_ == static_cast<int>(descriptors.size())) return;
  const std::size_t n = descriptors.size();
  distances.assign(n * n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const int d = descriptor_distance(descriptors[i], descriptors[j]);
      distances[i * n + j] = d;
      distances[j * n + i] = d;
    }
  }
  int best_median = std::numeric_limits<int>::max();
  std::size_t best = 0;
  row.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::copy(distances.begin() + static_cast<std::ptrdiff_t>(i * n),
              distances.begin() + static_cast<std::ptrdiff_t>((i + 1) * n), row.begin());
    std::nth_element(row.begin(), row.begin() + static_cast<std::ptrdiff_t>((n - 1) / 2), row.end());
    const int median = row[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = i;
    }
  }
  std::memcpy(descriptor_.data(), descriptors[best], descriptor_.size());
  descriptor_from_ = static_cast<int>(n);
}

void MapPoint::update_normal_and_depth(const ScalePyramid& pyramid) {
  if (bad_ || observations_.empty() || reference_ == nullptr) return;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto& [kf, idx] : observations_) {
    const Eigen::Vector3d d = position_ - kf->camera_center();
    normal += d.normalized();
    ++n;
  }
  const Eigen::Vector3d to_ref = position_ - reference_->camera_center();
  const double distance = to_ref.norm();
  const std::ptrdiff_t ref_index = index_in(reference_);
  const int level = ref_index >= 0 ? reference_->keypoint(static_cast<std::size_t>(ref_index)).octave : 0;
  max_distance_ = distance * pyramid.scale[static_cast<std::size_t>(level)];
  min_distance_ = max_distance_ / pyramid.scale[static_cast<std::size_t>(pyramid.n_levels - 1)];
  normal_ = (normal / n).normalized();
}

void MapPoint::set_bad() {
  if (bad_) return;
  const auto keep_alive = weak_from_this().lock();  // slots below may hold the last owners
  bad_ = true;
  const Observations observations = std::move(observations_);
  observations_.clear();
  num_observations_ = 0;
  descriptor_from_ = -1;
  for (const auto& [kf, idx] : observations) kf->erase_map_point(idx);
}

void MapPoint::replace_with(const std::shared_ptr<MapPoint>& other) {
  if (other.get() == this || bad_) return;
  const auto keep_alive = weak_from_this().lock();
  const Observations observations = std::move(observations_);
  observations_.clear();
  num_observations_ = 0;
  descriptor_from_ = -1;
  bad_ = true;
  replaced_by_ = other;
  for (const auto& [kf, idx] : observations) {
    if (!other->is_observed_by(kf)) {
      kf->set_map_point(idx, other);
      other->add_observation(kf, idx);
    } else {
      kf->erase_map_point(idx);
    }
  }
  other->increase_found(found_);
  other->increase_visible(visible_);
  // A fused point holds the people's observations too.
  if (on_dynamic_instance_) other->on_dynamic_instance_ = true;
  other->compute_distinctive_descriptor();
}

}  // namespace stillslam
