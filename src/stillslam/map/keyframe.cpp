#include "stillslam/map/keyframe.h"

#include <algorithm>

#include "stillslam/map/frame.h"

namespace stillslam {

namespace {
constexpr int kMinCovisibilityWeight = 15;
}

bool KeyFrameIdLess::operator()(const KeyFrame* a, const KeyFrame* b) const { return a->id() < b->id(); }

KeyFrame::KeyFrame(std::uint64_t id, const Frame& frame)
    : id_(id),
      frame_id_(frame.id()),
      timestamp_(frame.timestamp()),
      setup_(frame.setup_ptr()),
      T_cam_world_(frame.T_cam_world()),
      T_world_cam_(T_cam_world_.inverse()),
      keypoints_(frame.keypoints()),
      descriptors_(frame.descriptors()),
      u_right_(frame.u_right()),
      depth_(frame.depth()),
      grid_(frame.grid()),
      map_points_(frame.map_points()),
      origin_(id == 0) {}

Eigen::Isometry3d KeyFrame::T_cam_world_resolved() const {
  if (!bad_ || parent_ == nullptr) return T_cam_world_;
  return T_cam_parent_ * parent_->T_cam_world_resolved();
}

std::optional<Eigen::Vector3d> KeyFrame::unproject(std::size_t i) const {
  const float z = depth_[i];
  if (z <= 0) return std::nullopt;
  const cv::Point2f& pt = keypoints_[i].pt;
  return T_world_cam() * setup_->camera.unproject(Eigen::Vector2d(pt.x, pt.y), z);
}

int KeyFrame::num_tracked_points(int min_observations) const {
  int n = 0;
  for (const auto& mp : map_points_) {
    if (mp && !mp->is_bad() && mp->num_observations() >= min_observations) ++n;
  }
  return n;
}

void KeyFrame::add_connection(KeyFrame* other, int weight) {
  connections_[other] = weight;
  update_best_covisibles();
}

void KeyFrame::erase_connection(KeyFrame* other) {
  if (connections_.erase(other) > 0) update_best_covisibles();
}

int KeyFrame::weight(KeyFrame* other) const {
  const auto it = connections_.find(other);
  return it == connections_.end() ? 0 : it->second;
}

void KeyFrame::update_best_covisibles() {
  std::vector<std::pair<int, KeyFrame*>> pairs;
  pairs.reserve(connections_.size());
  for (const auto& [kf, w] : connections_) pairs.emplace_back(w, kf);
  // Decreasing weight; equal weights by increasing id (connections_ is id-ordered
  // and stable_sort keeps that order).
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  ordered_connections_.clear();
  ordered_weights_.clear();
  for (const auto& [w, kf] : pairs) {
    ordered_connections_.push_back(kf);
    ordered_weights_.push_back(w);
  }
}

std::vector<KeyFrame*> KeyFrame::covisibles() const { return ordered_connections_; }

std::vector<KeyFrame*> KeyFrame::best_covisibles(std::size_t n) const {
  const std::size_t m = std::min(n, ordered_connections_.size());
  return {ordered_connections_.begin(), ordered_connections_.begin() + static_cast<std::ptrdiff_t>(m)};
}

std::vector<KeyFrame*> KeyFrame::covisibles_with_weight(int min_weight) const {
  std::vector<KeyFrame*> out;
  for (std::size_t i = 0; i < ordered_connections_.size() && ordered_weights_[i] >= min_weight; ++i) {
    out.push_back(ordered_connections_[i]);
  }
  return out;
}

void KeyFrame::update_connections() {
  std::map<KeyFrame*, int, KeyFrameIdLess> counter;
  for (const auto& mp : map_points_) {
    if (!mp || mp->is_bad()) continue;
    for (const auto& [kf, idx] : mp->observations()) {
      if (kf == this || kf->is_bad()) continue;
      ++counter[kf];
    }
  }
  if (counter.empty()) return;

  int max_weight = 0;
  KeyFrame* best = nullptr;
  bool any_above = false;
  for (const auto& [kf, w] : counter) {
    if (w > max_weight) {
      max_weight = w;
      best = kf;
    }
    if (w >= kMinCovisibilityWeight) {
      kf->add_connection(this, w);
      any_above = true;
    }
  }
  if (!any_above) best->add_connection(this, max_weight);

  connections_ = std::move(counter);
  update_best_covisibles();

  if (first_connection_ && !origin_) {
    parent_ = ordered_connections_.front();
    parent_->add_child(this);
    first_connection_ = false;
  }
}

void KeyFrame::change_parent(KeyFrame* kf) {
  parent_ = kf;
  first_connection_ = false;  // an explicit parent is not replaced by the first connection's
  kf->add_child(this);
}

void KeyFrame::set_bad() {
  if (bad_ || origin_ || not_erase_ || parent_ == nullptr) return;
  const auto keep_alive = weak_from_this().lock();
  for (const auto& [kf, w] : connections_) kf->erase_connection(this);
  for (std::size_t i = 0; i < map_points_.size(); ++i) {
    const MapPointPtr mp = map_points_[i];
    if (mp) mp->erase_observation(this);
  }
  connections_.clear();
  ordered_connections_.clear();
  ordered_weights_.clear();

  // Re-parent the children: repeatedly attach the child with the strongest
  // covisibility edge to any keyframe already in the candidate set.
  std::set<KeyFrame*, KeyFrameIdLess> candidates{parent_};
  while (!children_.empty()) {
    int max_weight = -1;
    KeyFrame* best_child = nullptr;
    KeyFrame* best_parent = nullptr;
    for (KeyFrame* child : children_) {
      if (child->is_bad()) continue;
      for (KeyFrame* neighbour : child->covisibles()) {
        if (candidates.count(neighbour) == 0) continue;
        const int w = child->weight(neighbour);
        if (w > max_weight) {
          max_weight = w;
          best_child = child;
          best_parent = neighbour;
        }
      }
    }
    if (best_child == nullptr) break;
    best_child->change_parent(best_parent);
    candidates.insert(best_child);
    children_.erase(best_child);
  }
  for (KeyFrame* child : children_) child->change_parent(parent_);
  children_.clear();
  parent_->erase_child(this);
  T_cam_parent_ = T_cam_world_ * parent_->T_world_cam();
  bad_ = true;
}

}  // namespace stillslam
