#include "stillslam/tracking/motion_stage.h"

#include <algorithm>
#include <optional>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stillslam/features/brief_pattern.h"
#include "stillslam/map/map_point.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/tracking/instance_box_features.h"

namespace stillslam {

namespace {

// Checked first, so a bad value names its Motion key.
OrbOptions instance_orb(OrbOptions orb, const MotionOptions& options) {
  options.check();
  orb.n_features = options.instance_features;
  orb.check();
  return orb;
}

// Context around an instance's box for the ORB patch and the FAST border.
constexpr int kBoxPad = 2 * (BriefPattern::kRadius + 1);
// Fewer sampled pixels of an object (a sliver at the border): no verdict from depth.
constexpr int kMinFreeSpaceSamples = 30;

// `by_id` with each id replaced by to(id) (a map's values or a set's ids kept).
template <class ById, class To>
ById relabelled(const ById& by_id, const To& to) {
  ById out;
  for (const auto& entry : by_id) {
    if constexpr (requires { entry.second; }) {
      out[to(entry.first)] = entry.second;
    } else {
      out.insert(to(entry));
    }
  }
  return out;
}

}  // namespace

MotionStage::MotionStage(const PinholeCamera& camera, const OrbOptions& orb, std::vector<int> dynamic_class_ids,
                         int dilation_px, MotionOptions options)
    : camera_(camera),
      orb_(instance_orb(orb, options)),
      frame_features_(orb.n_features),
      dynamic_class_ids_(std::move(dynamic_class_ids)),
      dilation_px_(dilation_px),
      options_(std::move(options)),
      ids_(InstanceIdOptions{.min_iou = options_.min_iou}),
      check_(camera, options_.check_options()),
      places_(options_.places_options()) {}

void MotionStage::reset() {
  check_.reset();
  moving_.clear();
  places_.clear();
  alias_.clear();
  age_.clear();
  judged_ = 0;
  kept_since_.clear();
  depth_history_.clear();
  next_prediction_.reset();
}

std::uint32_t MotionStage::evidence_id(std::uint32_t stable) const {
  const auto it = alias_.find(stable);
  return it != alias_.end() ? it->second : stable;
}

std::uint32_t MotionStage::label_at(const cv::Point2f& p) const {
  if (labels_.empty()) return 0;
  const int u = std::clamp(static_cast<int>(std::lround(p.x)), 0, labels_.cols - 1);
  const int v = std::clamp(static_cast<int>(std::lround(p.y)), 0, labels_.rows - 1);
  return static_cast<std::uint32_t>(labels_(v, u));
}

bool MotionStage::masked(std::uint32_t id) const {
  return dynamic_ids_.count(id) ? !check_.is_static(id) : moving_.count(id) > 0;
}

cv::Mat1b MotionStage::mask_for(const std::vector<Detection>& detections, const cv::Mat1b& held, cv::Size size) {
  pending_ = true;
  prediction_ = next_prediction_;
  next_prediction_.reset();
  labels_ = cv::Mat1i::zeros(size);
  categories_.clear();
  stable_of_.clear();
  dynamic_ids_.clear();
  inside_ = MotionCheckFrame{};
  boxes_.clear();
  watched_ = cv::Mat1b::zeros(size);
  watched_ids_.clear();
  kept_pixels_ = cv::Mat1b();
  kept_boxes_.clear();
  extraction_mask_ = cv::Mat1b();
  std::vector<cv::Mat1b> kept_instances;
  std::vector<cv::Mat1b> masks;
  std::vector<int> classes;
  for (const Detection& d : detections) {
    // The same mask the class-only path makes of it (its box without a mask).
    masks.push_back(dynamic_instances({d}, {d.class_id}, size).front());
    classes.push_back(d.class_id);
  }
  const std::set<std::uint32_t> before = [&] {
    std::set<std::uint32_t> s;
    for (const TrackedInstance& t : ids_.tracked()) s.insert(t.id);
    return s;
  }();
  const std::vector<std::uint32_t> ids = ids_.assign(masks, classes);
  // Dropped ids: their evidence stays with their place (until InstancePlaces forgets it).
  std::set<std::uint32_t> alive;
  for (const TrackedInstance& t : ids_.tracked()) alive.insert(t.id);
  for (std::uint32_t id : before) {
    if (alive.count(id)) continue;
    alias_.erase(id);
    age_.erase(id);
  }
  std::vector<cv::Mat1b> masked_instances;
  for (std::size_t n = 0; n < masks.size(); ++n) {
    const std::uint32_t id = evidence_id(ids[n]);
    stable_of_[id] = ids[n];
    labels_.setTo(static_cast<int>(id), masks[n]);
    categories_[id] = detections[n].class_name;
    if (std::find(dynamic_class_ids_.begin(), dynamic_class_ids_.end(), classes[n]) != dynamic_class_ids_.end()) {
      dynamic_ids_.insert(id);
    }
    if (masked(id)) {
      masked_instances.push_back(masks[n]);
      boxes_.push_back(cv::boundingRect(masks[n]));
    } else if (options_.kept_features > 0 && dynamic_ids_.count(id)) {
      kept_instances.push_back(masks[n]);
      kept_boxes_.push_back(cv::boundingRect(masks[n]));
    } else if (options_.watch_objects && !dynamic_ids_.count(id)) {
      watched_.setTo(255, masks[n]);
      watched_ids_.insert(id);
      boxes_.push_back(cv::boundingRect(masks[n]));
    }
  }
  cv::Mat1b out = dynamic_mask(masked_instances, size, dilation_px_);
  if (!held.empty()) cv::bitwise_or(out, held, out);
  if (!kept_instances.empty()) {
    kept_pixels_ = cv::Mat1b::zeros(size);
    for (const cv::Mat1b& m : kept_instances) kept_pixels_.setTo(255, m);
    cv::bitwise_or(out, dynamic_mask(kept_instances, size, dilation_px_), extraction_mask_);
    kept_budget_ = options_.kept_features;
    if (options_.kept_features_area_factor > 0) {
      const double share = static_cast<double>(cv::countNonZero(kept_pixels_)) / (size.area());
      kept_budget_ = std::min(kept_budget_, static_cast<int>(std::lround(options_.kept_features_area_factor *
                                                                         frame_features_ * share)));
    }
  }
  return out;
}

OrbFeatures MotionStage::kept_features(const cv::Mat& gray) const {
  if (!pending_ || kept_pixels_.empty() || kept_budget_ <= 0) return {};
  return extract_in_boxes(orb_, kept_budget_, gray, kept_pixels_,
                          merge_instance_boxes(kept_boxes_, kBoxPad, gray.size()));
}

void MotionStage::collect(const cv::Mat& gray, const cv::Mat& depth, const cv::Mat1b& exclude,
                          const std::vector<cv::KeyPoint>& kept, const std::vector<cv::Point2f>& removed,
                          MotionFrameStats& stats) {
  if (!pending_) return;
  stats.judged = true;
  // Only the depth check (Motion.freeSpaceShare) keeps earlier depth images.
  const bool keep_depth = options_.free_space_share > 0 && !depth.empty() && depth.type() == CV_32F;
  depth_ = keep_depth ? depth.clone() : cv::Mat();
  // Each instance's place in the camera frame, from its pixels with depth:
  // the centroid's ray at the median depth (known from its first frame on,
  // features or not).
  mask_points_.clear();
  mask_pixels_.clear();
  if (!depth.empty()) {
    std::map<std::uint32_t, std::vector<double>> depths;
    std::map<std::uint32_t, Eigen::Vector3d> sums;  // u, v, count
    for (int v = 0; v < labels_.rows; v += 2) {
      for (int u = 0; u < labels_.cols; u += 2) {
        const auto id = static_cast<std::uint32_t>(labels_(v, u));
        const float z = depth.at<float>(v, u);
        if (id == 0 || !(z > 0)) continue;
        depths[id].push_back(z);
        sums.try_emplace(id, Eigen::Vector3d::Zero()).first->second += Eigen::Vector3d(u, v, 1);
      }
    }
    for (auto& [id, z] : depths) {
      if (z.size() < 10) continue;
      const Eigen::Vector3d& s = sums[id];
      const cv::KeyPoint centre(static_cast<float>(s.x() / s.z()), static_cast<float>(s.y() / s.z()), 1.f);
      const cv::Point2f c = camera_.undistort(std::vector<cv::KeyPoint>{centre}).front().pt;
      mask_points_[id] = camera_.unproject(Eigen::Vector2d(c.x, c.y), median_of(z));
      mask_pixels_[id] = static_cast<int>(4 * s.z());
    }
  }
  for (std::uint32_t id : dynamic_ids_) stats.static_instances += check_.is_static(id);
  for (const auto& [id, category] : categories_) stats.moving_instances += !dynamic_ids_.count(id) && moving_.count(id);
  const auto in_exclude = [&exclude](const cv::Point2f& p) {
    if (exclude.empty()) return true;
    return exclude(std::clamp(static_cast<int>(std::lround(p.y)), 0, exclude.rows - 1),
                   std::clamp(static_cast<int>(std::lround(p.x)), 0, exclude.cols - 1)) != 0;
  };
  for (const cv::Point2f& p : removed) {
    // Left out of the frame's extraction only for a kept person's own budget.
    if (!extraction_mask_.empty() && !in_exclude(p)) continue;
    const std::uint32_t id = label_at(p);
    if (id != 0 && !dynamic_ids_.count(id) && moving_.count(id)) {
      ++stats.features_removed_by_motion;
    } else {
      ++stats.features_removed_by_class;
    }
  }
  for (const cv::KeyPoint& kp : kept) {
    const std::uint32_t id = label_at(kp.pt);
    stats.features_kept_by_motion += id != 0 && dynamic_ids_.count(id);
  }
  cv::Mat1b inside = watched_.clone();
  if (!exclude.empty()) cv::bitwise_or(inside, exclude, inside);
  if (cv::countNonZero(inside) == 0) return;
  // The masked and watched instances' boxes only: their own small budget, apart from the frame's.
  const OrbFeatures f = extract_in_boxes(orb_, orb_.n_features, gray, inside,
                                         merge_instance_boxes(boxes_, kBoxPad, gray.size()));
  const std::vector<cv::KeyPoint> undistorted = camera_.undistort(f.keypoints);
  std::vector<int> rows;
  for (std::size_t i = 0; i < f.keypoints.size(); ++i) {
    const std::uint32_t id = label_at(f.keypoints[i].pt);
    if (id == 0) continue;  // the dilation margin or a held mask: not an instance's own pixel
    const cv::Point p(std::clamp(static_cast<int>(std::lround(f.keypoints[i].pt.x)), 0, gray.cols - 1),
                      std::clamp(static_cast<int>(std::lround(f.keypoints[i].pt.y)), 0, gray.rows - 1));
    const float z = depth.empty() ? 0.f : depth.at<float>(p);
    inside_.pixels.emplace_back(undistorted[i].pt.x, undistorted[i].pt.y);
    inside_.depth.push_back(z > 0 ? z : -1.f);
    inside_.instance.push_back(id);
    rows.push_back(static_cast<int>(i));
  }
  inside_.descriptors.create(static_cast<int>(rows.size()), f.descriptors.cols, f.descriptors.type());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    f.descriptors.row(rows[k]).copyTo(inside_.descriptors.row(static_cast<int>(k)));
  }
  stats.instance_features = static_cast<int>(rows.size());
}

void MotionStage::place_instances(const Frame& frame, std::vector<std::uint32_t>& frame_labels) {
  ++judged_;
  // Without a depth image: the per-axis median of its features' points with depth.
  std::map<std::uint32_t, std::vector<Eigen::Vector3d>> points;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame_labels[i] == 0 || frame.depth(i) <= 0) continue;
    const cv::Point2f& p = frame.keypoints()[i].pt;
    points[frame_labels[i]].push_back(camera_.unproject(Eigen::Vector2d(p.x, p.y), frame.depth(i)));
  }
  for (std::size_t i = 0; i < inside_.pixels.size(); ++i) {
    if (inside_.depth[i] <= 0) continue;
    points[inside_.instance[i]].push_back(camera_.unproject(inside_.pixels[i], inside_.depth[i]));
  }
  const Eigen::Isometry3d T_world_cam = frame.T_cam_world().inverse();
  std::set<std::uint32_t> present;
  std::map<std::uint32_t, Eigen::Vector3d> places;
  std::vector<PlaceClaim> claims;
  for (const auto& [id, category] : categories_) {
    present.insert(id);
    std::optional<Eigen::Vector3d> place;
    if (const auto m = mask_points_.find(id); m != mask_points_.end()) {
      place = T_world_cam * m->second;
    } else if (std::vector<Eigen::Vector3d>& pts = points[id]; pts.size() >= 3) {
      Eigen::Vector3d m;
      for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> v;
        for (const Eigen::Vector3d& q : pts) v.push_back(q[axis]);
        m[axis] = median_of(v);
      }
      place = T_world_cam * m;
    }
    if (!place) continue;
    places[id] = *place;
    // A new id (within its first span frames, not yet matched) may take over an earlier instance.
    const std::uint32_t stable = stable_of_[id];
    claims.push_back({id, category, *place, id == stable && age_[stable] < options_.span});
  }
  // old id -> the earlier instance it is (all relabelled at once: two ids may swap).
  const std::map<std::uint32_t, std::uint32_t> remap = places_.assign(claims, present);
  const auto to = [&remap](std::uint32_t id) {
    const auto it = remap.find(id);
    return it != remap.end() ? it->second : id;
  };
  if (!remap.empty()) {
    std::set<std::uint32_t> fresh;  // new ids: their own evidence and history go to the earlier instance
    for (const PlaceClaim& c : claims) {
      if (c.is_new && remap.count(c.id)) fresh.insert(c.id);
    }
    for (const auto& [from, earlier] : remap) {
      alias_[stable_of_[from]] = earlier;
      // An older id that jumped keeps its frames and evidence: they were another instance's.
      if (fresh.count(from)) {
        check_.relabel(from, earlier);
        moving_.erase(from);
      }
    }
    for (std::uint32_t& l : frame_labels) l = to(l);
    for (std::uint32_t& l : inside_.instance) l = to(l);
    for (int v = 0; v < labels_.rows; ++v) {
      for (int u = 0; u < labels_.cols; ++u) {
        if (labels_(v, u) != 0) labels_(v, u) = static_cast<int>(to(static_cast<std::uint32_t>(labels_(v, u))));
      }
    }
    categories_ = relabelled(categories_, to);
    mask_pixels_ = relabelled(mask_pixels_, to);
    stable_of_ = relabelled(stable_of_, to);
    dynamic_ids_ = relabelled(dynamic_ids_, to);
    places = relabelled(places, to);
  }
  for (const auto& [id, category] : categories_) {
    ++age_[stable_of_[id]];
    const auto place = places.find(id);
    const auto area = mask_pixels_.find(id);
    places_.seen(id, category, judged_, place != places.end() ? &place->second : nullptr,
                 area != mask_pixels_.end() ? area->second : 0);
  }
  for (std::uint32_t gone : places_.expire(judged_)) {
    check_.forget(gone);
    moving_.erase(gone);
    for (auto it = alias_.begin(); it != alias_.end();) it = it->second == gone ? alias_.erase(it) : std::next(it);
  }
}

const InstanceMotionState* MotionStage::state_of(const MotionCheckResult& r, std::uint32_t id) {
  const auto s = std::find_if(r.instances.begin(), r.instances.end(),
                              [id](const InstanceMotionState& st) { return static_cast<std::uint32_t>(st.id) == id; });
  return s != r.instances.end() ? &*s : nullptr;
}

void MotionStage::complete_check_frame(MotionCheckFrame& f, const Eigen::Isometry3d& T_cam_world,
                                       const cv::Mat& descriptors, const std::vector<int>& rows) const {
  f.T_cam_world = T_cam_world;
  f.categories = categories_;
  for (const auto& [id, category] : categories_) {
    if (!dynamic_ids_.count(id)) f.objects.insert(id);
  }
  f.descriptors.create(static_cast<int>(rows.size()) + inside_.descriptors.rows, 32, CV_8UC1);
  int row = 0;
  for (int i : rows) descriptors.row(i).copyTo(f.descriptors.row(row++));
  for (int k = 0; k < inside_.descriptors.rows; ++k) inside_.descriptors.row(k).copyTo(f.descriptors.row(row++));
  f.pixels.insert(f.pixels.end(), inside_.pixels.begin(), inside_.pixels.end());
  f.depth.insert(f.depth.end(), inside_.depth.begin(), inside_.depth.end());
  f.instance.insert(f.instance.end(), inside_.instance.begin(), inside_.instance.end());
}

void MotionStage::judge_objects_by_depth(const Frame& frame, const MotionCheckResult& r) {
  if (options_.free_space_share <= 0 || depth_.empty() || camera_.has_distortion()) {
    depth_history_.clear();
    return;
  }
  cv::Mat1b people;
  if (options_.free_space.count_nearer) {
    people = cv::Mat1b::zeros(labels_.size());
    for (int v = 0; v < labels_.rows; ++v) {
      const int* l = labels_.ptr<int>(v);
      std::uint8_t* out = people.ptr<std::uint8_t>(v);
      for (int u = 0; u < labels_.cols; ++u) {
        const auto id = static_cast<std::uint32_t>(l[u]);
        if (id != 0 && dynamic_ids_.count(id) && masked(id)) out[u] = 255;
      }
    }
  }
  depth_history_.push_back({frame.T_cam_world(), depth_, people,
                            options_.free_space_vacated ? labels_.clone() : cv::Mat1i()});
  const int frames = options_.free_space_span();
  if (static_cast<int>(depth_history_.size()) > frames + 1) depth_history_.pop_front();
  if (static_cast<int>(depth_history_.size()) < frames + 1) return;
  // Objects the matched features gave no verdict this frame.
  std::set<std::uint32_t> ids{0};
  for (const auto& [id, category] : categories_) {
    if (dynamic_ids_.count(id) || moving_.count(id)) continue;
    const InstanceMotionState* s = state_of(r, id);
    if (!s || s->verdict == MotionVerdict::NoEvidence) ids.insert(id);
  }
  if (ids.size() == 1) return;
  for (std::uint32_t id : moving_by_depth(frame.T_cam_world(), depth_history_.front(), ids)) moving_.insert(id);
}

std::set<std::uint32_t> MotionStage::moving_by_depth(const Eigen::Isometry3d& T_cam_world, const DepthView& earlier,
                                                     const std::set<std::uint32_t>& ids) const {
  const Eigen::Isometry3d T_earlier_current = earlier.T_cam_world * T_cam_world.inverse();
  const auto counts = count_seen_through(camera_, depth_, labels_, ids, T_earlier_current, earlier.depth,
                                         options_.free_space, earlier.people);
  std::set<std::uint32_t> out;
  // The other way round: the object's earlier pixels where this view sees farther (it left them).
  if (options_.free_space_vacated) {
    FreeSpaceOptions o = options_.free_space;
    o.count_nearer = false;
    const auto vacated =
        count_seen_through(camera_, earlier.depth, earlier.labels, ids, T_earlier_current.inverse(), depth_, o);
    for (const auto& [id, c] : vacated) {
      if (id == 0 || c.samples < kMinFreeSpaceSamples) continue;
      if (c.share() >= std::max(options_.free_space_share, 3 * vacated.at(0).share())) out.insert(id);
    }
  }
  const double background = counts.at(0).share();
  for (const auto& [id, c] : counts) {
    if (id == 0 || c.samples < kMinFreeSpaceSamples) continue;
    if (c.share() >= std::max(options_.free_space_share, 3 * background)) out.insert(id);
  }
  return out;
}

cv::Mat1b MotionStage::judge_predicted(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& descriptors,
                                       MotionFrameStats& stats) {
  if (!pending_ || !options_.predicted_check || !prediction_ || watched_ids_.empty()) return {};
  // The frame as on_tracked() gives it to the check, at the predicted pose;
  // a watched object is judged on its own features.
  MotionCheckFrame f;
  const std::vector<cv::KeyPoint> undistorted = camera_.undistort(keypoints);
  std::vector<int> rows;
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const std::uint32_t id = label_at(keypoints[i].pt);
    if (watched_ids_.count(id)) continue;
    rows.push_back(static_cast<int>(i));
    f.pixels.emplace_back(undistorted[i].pt.x, undistorted[i].pt.y);
    f.depth.push_back(-1.f);  // the current view's depth takes no part in a residual
    f.instance.push_back(id);
  }
  complete_check_frame(f, *prediction_, descriptors, rows);
  const MotionCheckResult r = check_.peek(f);
  std::set<std::uint32_t> found, no_verdict{0};
  for (std::uint32_t id : watched_ids_) {
    if (moving_.count(id)) continue;
    const InstanceMotionState* s = state_of(r, id);
    if (s && s->verdict == MotionVerdict::Disagrees) {
      found.insert(id);
    } else if (!s || s->verdict == MotionVerdict::NoEvidence) {
      no_verdict.insert(id);
    }
  }
  // Objects without a verdict from their features: from depth, against the
  // view that will lie free_space_span() judged frames before this one.
  const auto frames = static_cast<std::size_t>(options_.free_space_span());
  if (options_.free_space_share > 0 && !depth_.empty() && !camera_.has_distortion() && no_verdict.size() > 1 &&
      depth_history_.size() >= frames) {
    const DepthView& earlier = depth_history_[depth_history_.size() - frames];
    for (std::uint32_t id : moving_by_depth(*prediction_, earlier, no_verdict)) found.insert(id);
  }
  if (found.empty()) return {};
  std::vector<cv::Mat1b> masks;
  for (std::uint32_t id : found) {
    moving_.insert(id);
    masks.push_back(labels_ == static_cast<int>(id));
  }
  stats.moving_instances += static_cast<int>(found.size());
  stats.predicted_moving_instances = static_cast<int>(found.size());
  return dynamic_mask(masks, labels_.size(), dilation_px_);
}

int MotionStage::on_tracked(const Frame& frame, bool tracked) {
  if (!pending_) return 0;
  pending_ = false;
  if (!tracked || !frame.has_pose()) {
    reset();
    return 0;
  }
  std::vector<std::uint32_t> frame_labels(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) frame_labels[i] = label_at(frame.keypoints_raw()[i].pt);
  // A watched object is judged on its own features (collect()), not on the frame's there too.
  std::vector<int> judged_rows;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (!watched_ids_.count(frame_labels[i])) judged_rows.push_back(static_cast<int>(i));
  }
  place_instances(frame, frame_labels);
  MotionCheckFrame f;
  for (int i : judged_rows) {
    const cv::Point2f& p = frame.keypoints()[static_cast<std::size_t>(i)].pt;
    f.pixels.emplace_back(p.x, p.y);
    f.depth.push_back(frame.depth(static_cast<std::size_t>(i)));
    f.instance.push_back(frame_labels[static_cast<std::size_t>(i)]);
  }
  complete_check_frame(f, frame.T_cam_world(), frame.descriptors(), judged_rows);
  const MotionCheckResult r = check_.add(std::move(f));
  for (const InstanceMotionState& s : r.instances) {
    const auto id = static_cast<std::uint32_t>(s.id);
    if (dynamic_ids_.count(id)) continue;
    if (s.verdict == MotionVerdict::Disagrees) moving_.insert(id);
    if (s.is_static) moving_.erase(id);
  }
  judge_objects_by_depth(frame, r);
  // Map points seen on an instance that is now judged moving leave the map;
  // those seen on a person kept as static are flagged so no saved map holds them.
  int culled = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame_labels[i] == 0) continue;
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp || mp->is_bad()) continue;
    if (masked(frame_labels[i])) {
      mp->set_bad();
      ++culled;
    } else if (dynamic_ids_.count(frame_labels[i])) {
      mp->mark_on_dynamic_instance();
      if (options_.kept_point_frames == 0) continue;
      const auto since = kept_since_.try_emplace(mp->id(), frame.id()).first;
      if (frame.id() >= since->second + static_cast<std::uint64_t>(options_.kept_point_frames)) {
        mp->set_bad();
        ++culled;
        kept_since_.erase(since);
      }
    }
  }
  // Points never matched again: forgotten once well past the limit.
  if (kept_since_.size() > 4096) {
    for (auto it = kept_since_.begin(); it != kept_since_.end();) {
      it = frame.id() > it->second + 4 * static_cast<std::uint64_t>(options_.kept_point_frames) ? kept_since_.erase(it)
                                                                                                 : std::next(it);
    }
  }
  return culled;
}

}  // namespace stillslam
