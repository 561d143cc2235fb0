#include "stillslam/tracking/tracker.h"

#include <algorithm>
#include <numeric>
#include <unordered_set>
#include <utility>

#include "stillslam/map/projection_search.h"
#include "stillslam/tracking/depth_point_check.h"
#include "stillslam/tracking/keyframe_admission.h"
#include "stillslam/tracking/local_map.h"
#include "stillslam/tracking/pose_refinement.h"
#include "stillslam/tracking/sparse_view.h"
#include "stillslam/tracking/static_evidence.h"

namespace stillslam {

namespace {
constexpr int kMinMotionMatches = 20;
constexpr int kMinMotionInliers = 10;
constexpr int kMinReferenceMatches = 15;
constexpr std::uint64_t kTemporaryPointIdBase = 1ULL << 62;  // never collides with map ids

// The constant velocity of a motion over `frames` frames: its rotation angle
// and translation divided evenly (close to the exact root for small turns).
Eigen::Isometry3d per_frame_motion(const Eigen::Isometry3d& motion, int frames) {
  if (frames <= 1) return motion;
  const Eigen::AngleAxisd turn(motion.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(turn.angle() / frames, turn.axis()).toRotationMatrix();
  out.translation() = motion.translation() / frames;
  return out;
}
}  // namespace

Tracker::Tracker(Map& map, TrackerOptions options, LocalMappingLink link)
    : map_(&map), options_(options), link_(std::move(link)), centre_filter_(options_.sparse_view.filter_gain) {
  options_.check();
  keyframe_budget_ = KeyFrameBudget(options_.keyframe_budget);
}

void Tracker::start_new_map(Map& map) {
  map_ = &map;
  state_ = TrackingState::NotInitialized;
  last_frame_ = Frame();
  T_last_ref_ = Eigen::Isometry3d::Identity();
  velocity_.reset();
  reference_keyframe_.reset();
  last_keyframe_.reset();
  last_keyframe_frame_id_ = 0;
  keyframe_budget_.reset();
  last_lost_frame_id_ = 0;
  was_lost_ = false;
  start_candidate_.reset();
  start_confirming_.clear();
  start_keep_.clear();
  start_confirmed_.clear();
  start_matched_.clear();
  last_frame_left_out_.clear();
  past_poses_.clear();
  centre_filter_.stop();
  start_confirmations_ = 0;
  start_frames_rejected_ = 0;
  start_gap_frames_ = 1;
  start_evidence_.reset();
}

void Tracker::switch_map(Map& map) { map_ = &map; }

void Tracker::localize_in(Map& map) {
  start_new_map(map);
  state_ = TrackingState::Lost;
}

TrackingResult Tracker::track(Frame& frame) {
  std::lock_guard<std::mutex> lock(map_->update_mutex());
  TrackingResult result;
  std::string start_note;  // how the map started, when it started from an earlier frame at this one
  if (state_ == TrackingState::NotInitialized) {
    if (options_.localization_only) {
      result.state = state_;
      result.reason = "localization only: no map to track";
      return result;
    }
    if (refuse_sparse_start(frame, result)) return result;
    const Start start = try_to_start_map(frame, result);
    if (start == Start::Waiting) {
      result.state = state_;
      return result;
    }
    if (start == Start::FromThisFrame) {
      result.state = state_;
      result.reason = "initialized";
      result.new_keyframe = true;
      result.inliers = frame.num_matches();
      result.reference = reference_keyframe_;
      result.T_cam_reference = Eigen::Isometry3d::Identity();
      return result;
    }
    // Started from an earlier frame: this one is tracked against it.
    start_note = std::move(result.reason);
    result.reason.clear();
  }

  update_last_frame();
  motion_prior_.reset();
  bool ok = false;
  if (state_ == TrackingState::Ok) {
    if (velocity_) ok = track_with_motion_model(frame, result);
    if (!ok) ok = track_reference_keyframe(frame, result);
  } else {
    ok = track_while_lost(frame, result);
  }
  if (ok) ok = track_local_map(frame, result);
  ok = sparse_view_fallback(frame, result, ok);

  // After a start from an earlier frame the last frame lies that many frames back (once).
  const int frames_since_last = std::exchange(start_gap_frames_, 1);
  if (ok) {
    const bool recovered = state_ == TrackingState::Lost;
    if (result.relocalized) result.reason = "relocalized";
    if (recovered) {
      was_lost_ = true;
      last_lost_frame_id_ = frame.id();
    }
    state_ = TrackingState::Ok;
    // After a loss the last good frame may be far back in time: no velocity.
    if (last_frame_.has_pose() && !recovered) {
      velocity_ = per_frame_motion(frame.T_cam_world() * last_frame_.T_cam_world().inverse(), frames_since_last);
    } else {
      velocity_.reset();
      past_poses_.clear();
    }
    // The keypoints whose match this frame rejected, in the start's window:
    // neither keyframe nor visual-odometry points.
    const bool start_window = start_evidence_.active(frame.id());
    std::vector<bool> rejected;
    if (start_window) {
      rejected.assign(frame.size(), false);
      for (std::size_t i = 0; i < frame.size(); ++i) rejected[i] = frame.map_point(i) && frame.is_outlier(i);
    }
    // A predicted pose matched nothing: no keyframe from it.
    // Nor from a sparse view when the fallback makes none (SparseViewOptions::keyframes).
    const bool sparse_keyframe = options_.sparse_view.keyframes || !is_sparse_view(frame, options_.sparse_view);
    bool want_keyframe = !options_.localization_only && result.sparse_view != SparseView::Predicted &&
                         sparse_keyframe && need_new_keyframe(frame, result.inliers);
    if (want_keyframe && options_.max_keyframe_mask_age >= 0 && frame.mask_age() > options_.max_keyframe_mask_age) {
      result.keyframe_deferred = true;  // no map points from a stale mask: a later frame
      want_keyframe = false;
    }
    if (want_keyframe) {
      // SparseViewOptions::keyframe_prior_sigma: from the inliers, before the keyframe takes the matches.
      std::optional<KeyFrame::CentrePrior> centre_prior;
      if (options_.sparse_view.keyframe_prior_sigma > 0 && result.sparse_view == SparseView::Tracked) {
        centre_prior = sparse_keyframe_prior(frame);
      }
      create_keyframe(frame, start_window);
      if (centre_prior) frame.reference_keyframe()->set_centre_prior(*centre_prior);
      result.new_keyframe = true;
      if (options_.probe) options_.probe(TrackingStage::NewKeyFrame, frame, *map_);
    }
    // Outliers found in the final optimization do not carry over.
    discard_outliers(frame);
    if (!frame.reference_keyframe()) frame.set_reference_keyframe(reference_keyframe_);
    reference_keyframe_ = frame.reference_keyframe();
    T_last_ref_ = frame.T_cam_world() * reference_keyframe_->T_world_cam();
    if (options_.sparse_view.filter_gain > 0) {
      past_poses_.push_back({frame.id(), reference_keyframe_, T_last_ref_});
      while (past_poses_.size() > static_cast<std::size_t>(options_.sparse_view.filter_frames) + 1) {
        past_poses_.pop_front();
      }
    }
    result.reference = reference_keyframe_;
    result.T_cam_reference = T_last_ref_;
    last_frame_ = frame;
    last_frame_left_out_ = std::move(rejected);
  } else {
    state_ = TrackingState::Lost;
    velocity_.reset();
    past_poses_.clear();
    centre_filter_.stop();
    if (result.reason.empty()) result.reason = "lost";
  }
  if (!start_note.empty()) result.reason = start_note + "; " + result.reason;
  result.state = state_;
  return result;
}

bool Tracker::refuse_sparse_start(const Frame& frame, TrackingResult& result) {
  if (!is_sparse_view(frame, options_.sparse_view)) return false;
  const std::string dropped = drop_start_candidate();
  result.state = state_;
  result.sparse_view = SparseView::NoStart;
  result.reason = "the masks hide " + std::to_string(static_cast<int>(100 * masked_share(frame))) +
                  " % of the view: no map starts from it" + dropped;
  return true;
}

bool Tracker::sparse_view_fallback(Frame& frame, TrackingResult& result, bool ok) {
  if (!is_sparse_view(frame, options_.sparse_view)) {
    centre_filter_.stop();
    return ok;
  }
  if (ok && result.inliers >= options_.sparse_view.inliers) {
    result.sparse_view = SparseView::Tracked;
    if (options_.sparse_view.filter_gain > 0) filter_sparse_centre(frame, result);
    return true;
  }
  centre_filter_.stop();
  // Only while tracking: after a loss there is no velocity to predict with.
  if (state_ != TrackingState::Ok || !velocity_ || !last_frame_.has_pose()) return ok;
  const Eigen::Isometry3d predicted = *velocity_ * last_frame_.T_cam_world();
  if (ok) {
    frame.set_pose(blend_poses(predicted, frame.T_cam_world(), options_.sparse_view.tracked_weight));
    result.sparse_view = SparseView::Blended;
    return true;
  }
  // The failed matches do not carry over to the next frame.
  frame.clear_map_points();
  frame.set_pose(predicted);
  result.sparse_view = SparseView::Predicted;
  result.reason = "sparse view: constant-velocity prediction";
  return true;
}

void Tracker::filter_sparse_centre(Frame& frame, TrackingResult& result) {
  // Only while tracking, from the last frame's pose through its reference keyframe.
  if (state_ != TrackingState::Ok || !last_frame_.has_pose() || past_poses_.empty() ||
      past_poses_.back().frame_id >= frame.id()) {
    centre_filter_.stop();
    return;
  }
  const auto centre_of = [](const PastPose& p) {
    return Eigen::Vector3d((p.T_cam_reference * p.reference->T_cam_world()).inverse().translation());
  };
  const PastPose& last = past_poses_.back();
  const PastPose& first = past_poses_.front();
  Eigen::Vector3d start_velocity = Eigen::Vector3d::Zero();
  if (last.frame_id > first.frame_id) {
    start_velocity = (centre_of(last) - centre_of(first)) / static_cast<double>(last.frame_id - first.frame_id);
  }
  const Eigen::Vector3d tracked = frame.camera_center();
  const Eigen::Vector3d filtered = centre_filter_.step(centre_of(last), start_velocity, tracked,
                                                       static_cast<int>(frame.id() - last.frame_id));
  // The pose again from the inliers, its centre held at the filtered one
  // along the pose's least certain directions (SparseViewOptions::filter_axes).
  const std::vector<PoseObservation> observations = inlier_observations(frame);
  if (options_.sparse_view.filter_axes < 3) {
    result.sparse_filter_projection = weak_axes_projection(
        centre_covariance(frame.setup().camera, frame.T_cam_world(), observations), options_.sparse_view.filter_axes);
  }
  const Eigen::Vector3d centre = options_.sparse_view.filter_axes < 3
                                     ? Eigen::Vector3d(tracked + result.sparse_filter_projection * (filtered - tracked))
                                     : filtered;
  PosePrior prior;
  prior.T_cam_world = frame.T_cam_world();
  prior.T_cam_world.translation() = -(prior.T_cam_world.linear() * centre);
  prior.sigma_translation = 1e-4;
  prior.sigma_rotation = 1.0;  // the rotation follows the points
  const PoseOptimizationResult held =
      optimize_pose(frame.setup().camera, prior.T_cam_world, observations, options_.pose, &prior);
  frame.set_pose(held.T_cam_world);
}

KeyFrame::CentrePrior Tracker::sparse_keyframe_prior(const Frame& frame) const {
  const std::vector<PoseObservation> observations = inlier_observations(frame);
  const Eigen::Matrix3d projection = weak_axes_projection(
      centre_covariance(frame.setup().camera, frame.T_cam_world(), observations), options_.sparse_view.filter_axes);
  KeyFrame::CentrePrior prior;
  prior.mean = frame.camera_center();
  prior.sqrt_info = projection / options_.sparse_view.keyframe_prior_sigma;
  return prior;
}

Tracker::Start Tracker::try_to_start_map(Frame& frame, TrackingResult& result) {
  if (frame.num_with_depth() < options_.init_min_keypoints) {
    const std::string dropped = drop_start_candidate();
    result.reason = "waiting for a frame with " + std::to_string(options_.init_min_keypoints) +
                    " keypoints with depth (has " + std::to_string(frame.num_with_depth()) + ")" + dropped;
    return Start::Waiting;
  }
  // The first keyframe's points enter the map like any keyframe's: not from a stale mask.
  const bool stale_mask =
      options_.max_keyframe_mask_age >= 0 && frame.mask_age() > options_.max_keyframe_mask_age;
  // Without segmentation only the geometric check guards the start; after a long wait, take what comes.
  const bool unmasked = frame.dynamic_mask().empty();
  const int confirm_frames = unmasked ? options_.init_unmasked_confirm_frames : options_.init_confirm_frames;
  if (!stale_mask && ((unmasked && confirm_frames == 0) || start_frames_rejected_ >= options_.init_wait_frames)) {
    start_confirming_.clear();  // a candidate left after the last rejection gets no pose
    initialize(frame, frame);
    return Start::FromThisFrame;
  }
  if (start_candidate_) {
    const InitialViewCheck check = check_initial_view(*start_candidate_, frame, options_.initial_view);
    if (check.accepted) {
      for (std::size_t i = 0; i < start_keep_.size(); ++i) {
        start_keep_[i] = start_keep_[i] && check.keep[i];
        start_confirmed_[i] = start_confirmed_[i] || check.confirmed[i];
        start_matched_[i] = start_matched_[i] || check.matched[i];
      }
      const auto [matched, moving] = start_tally();
      const std::string tally = std::to_string(moving) + " of " + std::to_string(matched) +
                                " matched first-frame points found moving";
      if (++start_confirmations_ >= confirm_frames) {
        Frame first = std::move(*start_candidate_);
        // Without masks the check filters only when it found something moving.
        const bool filter = !unmasked || (moving >= options_.init_unmasked_moving_points &&
                                          moving >= options_.init_unmasked_moving_share * matched);
        std::vector<bool> keep;
        if (filter) {
          keep = std::move(start_keep_);
          // Without masks a point nothing confirmed may be a mover no frame matched.
          for (std::size_t i = 0; unmasked && i < keep.size(); ++i) keep[i] = keep[i] && start_confirmed_[i];
        }
        const std::uint64_t first_id = first.id();
        start_candidate_.reset();
        initialize(first, frame, keep);
        if (unmasked) {
          result.reason = "map started at frame " + std::to_string(first_id) + ", " + tally +
                          (filter ? ": left out of the first keyframe" : ": first keyframe kept whole");
        } else {
          result.reason = "map started at frame " + std::to_string(first_id) + ", confirmed by " +
                          std::to_string(start_confirmations_) + " frames";
        }
        if (unmasked && filter && options_.init_unmasked_trust_frames > 0) {
          start_evidence_.begin(reference_keyframe_->map_points(),
                                frame.id() + static_cast<std::uint64_t>(options_.init_unmasked_trust_frames));
        }
        // The first frame is at identity: the motion model starts this frame
        // at the check's PnP motion, however many frames were dropped between.
        velocity_ = check.T_next_first;
        start_gap_frames_ = static_cast<int>(std::max<std::uint64_t>(frame.id() - first_id, 1));
        result.start_frames = pose_start_frames(std::move(first));
        return Start::FromAnEarlierFrame;
      }
      // Posed once the map starts from the candidate: the check's motion from it.
      ConfirmingFrame waited{frame, check.next_keypoint};
      waited.frame.set_pose(check.T_next_first);
      start_confirming_.push_back(std::move(waited));
      result.reason = "first keyframe confirmed by " + std::to_string(start_confirmations_) + " of " +
                      std::to_string(confirm_frames) + " frames" + (unmasked ? ", " + tally : "");
      return Start::Waiting;
    }
    ++start_frames_rejected_;
    result.reason = check.reason + drop_start_candidate();
  } else {
    result.reason = "checking the first keyframe against the next frames";
  }
  if (stale_mask) {
    const std::string dropped = drop_start_candidate();
    result.keyframe_deferred = true;  // asks for the next segmentation slot
    result.reason =
        "waiting for a fresher mask to start the map (mask age " + std::to_string(frame.mask_age()) + ")" + dropped;
    return Start::Waiting;
  }
  start_candidate_ = frame;
  start_confirming_.clear();
  start_keep_.assign(frame.size(), true);
  start_confirmed_.assign(frame.size(), false);
  start_matched_.assign(frame.size(), false);
  start_confirmations_ = 0;
  return Start::Waiting;
}

std::string Tracker::drop_start_candidate() {
  std::string note;
  if (start_candidate_) {
    note = "; the start candidate (frame " + std::to_string(start_candidate_->id()) + ")";
    if (!start_confirming_.empty()) {
      note += " and the " + std::to_string(start_confirming_.size()) + " frame" +
              (start_confirming_.size() > 1 ? "s" : "") + " that confirmed it (to frame " +
              std::to_string(start_confirming_.back().frame.id()) + ")";
    }
    note += start_confirming_.empty() ? " gets no pose" : " get no pose";
  }
  start_candidate_.reset();
  start_confirming_.clear();
  return note;
}

std::vector<StartFramePose> Tracker::pose_start_frames(Frame first) {
  const KeyFramePtr kf = reference_keyframe_;
  std::vector<StartFramePose> out;
  out.reserve(1 + start_confirming_.size());
  const Eigen::Isometry3d T_first_ref = first.T_cam_world() * kf->T_world_cam();
  out.push_back({std::move(first), kf, T_first_ref, true});
  for (ConfirmingFrame& c : start_confirming_) {
    Frame& f = c.frame;
    // Its confirmed matches now see the first keyframe's points (those the start kept).
    for (std::size_t i = 0; i < c.candidate_matches.size(); ++i) {
      const int j = c.candidate_matches[i];
      if (j < 0 || !kf->map_point(i)) continue;
      f.set_map_point(static_cast<std::size_t>(j), kf->map_point(i));
    }
    // Motion-only BA from the PnP motion (with the depths the PnP left out);
    // with too few inliers the PnP motion stays.
    const Eigen::Isometry3d pnp = f.T_cam_world();
    if (refine_pose(f, options_.pose) < kMinMotionInliers) f.set_pose(pnp);
    discard_outliers(f);
    f.set_reference_keyframe(kf);
    const Eigen::Isometry3d T_cam_ref = f.T_cam_world() * kf->T_world_cam();
    out.push_back({std::move(f), kf, T_cam_ref, false});
  }
  start_confirming_.clear();
  return out;
}

std::pair<int, int> Tracker::start_tally() const {
  int matched = 0, moving = 0;
  for (std::size_t i = 0; i < start_matched_.size(); ++i) {
    if (!start_matched_[i]) continue;
    ++matched;
    if (!start_keep_[i]) ++moving;
  }
  return {matched, moving};
}

void Tracker::initialize(Frame& frame, const Frame& tracked, const std::vector<bool>& keep) {
  start_frames_rejected_ = 0;
  frame.set_pose(Eigen::Isometry3d::Identity());
  KeyFramePtr kf = map_->create_keyframe(frame);
  // The rule on the map's first keyframe only with NearPersonOptions::at_start.
  const std::vector<char> near_person = options_.near_person.at_start
                                            ? near_carried_person(frame, options_.near_person)
                                            : std::vector<char>(frame.size(), 0);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto p = kf->unproject(i);
    if (!p || (!keep.empty() && !keep[i])) continue;
    if (near_person[i]) {
      ++near_person_skipped_;
      continue;
    }
    MapPointPtr mp = map_->create_map_point(*p, kf.get());
    mp->add_observation(kf.get(), i);
    kf->set_map_point(i, mp);
    mp->compute_distinctive_descriptor();
    mp->update_normal_and_depth(frame.setup().pyramid);
    frame.set_map_point(i, mp);
  }
  frame.set_reference_keyframe(kf);
  reference_keyframe_ = kf;
  last_keyframe_ = kf;
  last_keyframe_frame_id_ = frame.id();
  keyframe_budget_.spend(frame.timestamp());
  T_last_ref_ = Eigen::Isometry3d::Identity();
  last_frame_ = frame;
  // What the start check left out (a mover) is no visual-odometry point either.
  last_frame_left_out_.assign(frame.size(), false);
  for (std::size_t i = 0; i < keep.size(); ++i) last_frame_left_out_[i] = !keep[i];
  state_ = TrackingState::Ok;
  if (options_.probe) options_.probe(TrackingStage::NewKeyFrame, frame, *map_);
  if (link_.insert_keyframe) link_.insert_keyframe(kf, tracked);
}

// Re-anchors the last frame on its reference keyframe (which local BA may
// have moved) and gives it temporary "visual odometry" points from its close
// depths so the motion model has enough to match against (not added to the map).
void Tracker::update_last_frame() {
  if (!last_frame_.has_pose() || !reference_keyframe_) return;
  last_frame_.set_pose(T_last_ref_ * reference_keyframe_->T_cam_world_resolved());
  std::vector<std::pair<float, std::size_t>> by_depth;
  for (std::size_t i = 0; i < last_frame_.size(); ++i) {
    if (last_frame_.depth(i) > 0) by_depth.emplace_back(last_frame_.depth(i), i);
  }
  std::sort(by_depth.begin(), by_depth.end());
  int n = 0;
  const double close_depth = last_frame_.setup().close_depth;
  for (const auto& [z, i] : by_depth) {
    if (i < last_frame_left_out_.size() && last_frame_left_out_[i]) continue;
    const MapPointPtr& existing = last_frame_.map_point(i);
    if (!existing || existing->num_observations() < 1) {
      auto mp = std::make_shared<MapPoint>(kTemporaryPointIdBase + temporary_point_id_++,
                                           *last_frame_.unproject(i), nullptr);
      mp->set_descriptor(last_frame_.descriptor(i));
      last_frame_.set_map_point(i, std::move(mp));
      last_frame_.set_outlier(i, false);
    }
    ++n;
    if (z > close_depth && n > options_.new_keyframe_points) break;
  }
}

std::optional<Eigen::Isometry3d> Tracker::predicted_pose() const {
  if (state_ != TrackingState::Ok || !last_frame_.has_pose()) return std::nullopt;
  return velocity_ ? *velocity_ * last_frame_.T_cam_world() : last_frame_.T_cam_world();
}

bool Tracker::track_with_motion_model(Frame& frame, TrackingResult& result) {
  frame.set_pose(*velocity_ * last_frame_.T_cam_world());
  motion_prior_ = motion_prior(frame.T_cam_world(), options_.motion_prior);
  frame.clear_map_points();
  int matches = search_by_projection(frame, last_frame_, options_.motion_search_radius);
  if (matches < kMinMotionMatches) {
    frame.clear_map_points();
    matches = search_by_projection(frame, last_frame_, 2 * options_.motion_search_radius);
  }
  if (matches < kMinMotionMatches) {
    result.reason = "motion model: " + std::to_string(matches) + " matches";
    motion_prior_.reset();
    return false;
  }
  refine_stage_pose(frame, result);
  if (options_.probe) options_.probe(TrackingStage::MotionModel, frame, *map_);
  const int inliers = discard_outliers(frame);
  if (inliers < kMinMotionInliers) {
    result.reason = "motion model: " + std::to_string(inliers) + " inliers";
    motion_prior_.reset();  // the prediction did not hold
    return false;
  }
  return true;
}

int Tracker::search_points(Frame& frame, const std::vector<MapPointPtr>& points, float th) {
  std::unordered_set<const MapPoint*> matched;
  for (const auto& mp : frame.map_points()) {
    if (mp) matched.insert(mp.get());
  }
  std::vector<ProjectedPoint> candidates;
  for (const MapPointPtr& mp : points) {
    if (mp->is_bad() || matched.count(mp.get())) continue;
    auto projected = project_in_frustum(frame, mp);
    if (!projected) continue;
    mp->increase_visible();
    candidates.push_back(std::move(*projected));
  }
  return search_by_projection(frame, candidates, th);
}

bool Tracker::track_reference_keyframe(Frame& frame, TrackingResult& result) {
  // Without a vocabulary: project the reference keyframe's neighbourhood with
  // the last pose and a wide window.
  frame.set_pose(last_frame_.T_cam_world());
  frame.clear_map_points();
  const LocalMap local = build_local_map(frame, reference_keyframe_.get(), 10);
  int matches = search_points(frame, local.points, options_.reference_search_th);
  if (matches < kMinReferenceMatches) {
    // Faster motion than the window allows: three times wider.
    frame.clear_map_points();
    matches = search_points(frame, local.points, 3 * options_.reference_search_th);
  }
  if (matches < kMinReferenceMatches) {
    result.reason = "reference keyframe: " + std::to_string(matches) + " matches";
    return false;
  }
  refine_pose_on_evidence(frame, options_.pose, options_.static_evidence, nullptr, &start_evidence_);
  if (options_.probe) options_.probe(TrackingStage::ReferenceKeyFrame, frame, *map_);
  const int inliers = discard_outliers(frame);
  if (inliers < kMinMotionInliers) {
    result.reason = "reference keyframe: " + std::to_string(inliers) + " inliers";
    return false;
  }
  return true;
}

// The last keyframe, or its closest ancestor if local mapping culled it
// (localizing in a loaded map, which gets no new keyframes: the reference).
KeyFrame* Tracker::anchor_keyframe() const {
  KeyFrame* kf = last_keyframe_ ? last_keyframe_.get() : reference_keyframe_.get();
  while (kf != nullptr && kf->is_bad()) kf = kf->parent();
  return kf;
}

bool Tracker::track_while_lost(Frame& frame, TrackingResult& result) {
  if (link_.relocalize && link_.relocalize(frame)) {
    result.relocalized = true;
    return true;
  }
  if (!last_frame_.has_pose()) return false;
  frame.set_pose(last_frame_.T_cam_world());
  frame.clear_map_points();
  const LocalMap local = build_local_map(frame, anchor_keyframe(), 20);
  const int matches = search_points(frame, local.points, options_.lost_search_th);
  if (matches < options_.min_local_map_inliers) {
    result.reason = "lost: " + std::to_string(matches) + " matches in the last keyframes' local map";
    return false;
  }
  refine_pose(frame, options_.pose);
  if (options_.probe) options_.probe(TrackingStage::Lost, frame, *map_);
  const int inliers = discard_outliers(frame);
  if (inliers < options_.min_local_map_inliers) {
    result.reason = "lost: " + std::to_string(inliers) + " inliers in the last keyframes' local map";
    return false;
  }
  return true;
}

bool Tracker::track_local_map(Frame& frame, TrackingResult& result) {
  const LocalMap local = build_local_map(frame, anchor_keyframe(), options_.max_local_keyframes);
  if (local.reference != nullptr) {
    frame.set_reference_keyframe(local.reference->shared_from_this());
  }
  for (const auto& mp : frame.map_points()) {
    if (mp) mp->increase_visible();
  }
  const bool recovering = was_lost_ && frame.id() < last_lost_frame_id_ + 2;
  search_points(frame, local.points, recovering ? 5.f : options_.local_map_search_th);
  result.matches = frame.num_matches();
  refine_stage_pose(frame, result);
  if (options_.probe) options_.probe(TrackingStage::LocalMap, frame, *map_);
  int inliers = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp) continue;
    if (mp->num_observations() > 0) mp->record_tracking_match(!frame.is_outlier(i));
    if (mp->num_observations() > 0 && frame.is_outlier(i)) mp->record_outlier_frame(frame.id());
    if (frame.is_outlier(i)) continue;
    mp->increase_found();
    if (mp->num_observations() > 0) ++inliers;
  }
  result.inliers = inliers;
  cull_outlier_streaks(frame, inliers);
  if (inliers < options_.min_local_map_inliers) {
    result.reason = "local map: " + std::to_string(inliers) + " inliers";
    return false;
  }
  result.reason = "ok";
  return true;
}

// A map point matched in several consecutive frames and rejected by the pose
// optimization each time does not fit the camera motion: it moved (a thing
// the segmentation missed) or keeps being mismatched. Only while the frame
// is tracked well, so that a bad pose does not clear the map.
void Tracker::cull_outlier_streaks(const Frame& frame, int inliers) {
  if (options_.outlier_streak_cull <= 0 || options_.localization_only ||
      inliers < 2 * options_.min_local_map_inliers) {
    return;
  }
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (mp && frame.is_outlier(i) && mp->num_observations() > 0 && !mp->is_bad() &&
        mp->outlier_streak() >= options_.outlier_streak_cull) {
      mp->set_bad();
    }
  }
}

int Tracker::refine_stage_pose(Frame& frame, TrackingResult& result) {
  MotionPriorStep step;
  MotionPriorOptions prior_options = options_.motion_prior;
  if (options_.sparse_view.prior && is_sparse_view(frame, options_.sparse_view)) {
    prior_options.gate = 0;  // the crowd fallback: the prediction in every stage
    prior_options.refit = false;
  }
  const int inliers = refine_pose_with_prior(frame, options_.pose, options_.static_evidence, motion_prior_,
                                             prior_options, &step, &start_evidence_);
  result.motion_prior.add(step);
  return inliers;
}

bool Tracker::need_new_keyframe(const Frame& frame, int inliers) const {
  const std::size_t num_keyframes = map_->num_keyframes();
  const std::uint64_t since_last = frame.id() - last_keyframe_frame_id_;
  if (was_lost_ && frame.id() < last_lost_frame_id_ + static_cast<std::uint64_t>(options_.max_frames_between_keyframes) &&
      num_keyframes > static_cast<std::size_t>(options_.max_frames_between_keyframes)) {
    return false;
  }
  const int min_observations = num_keyframes <= 2 ? 2 : 3;
  const int reference_matches = reference_keyframe_ ? reference_keyframe_->num_tracked_points(min_observations) : 0;
  const bool idle = link_.accepts_keyframes ? link_.accepts_keyframes(frame.timestamp()) : true;

  // Close points: tracked vs. not tracked (new structure worth a keyframe).
  int tracked_close = 0, untracked_close = 0;
  const double close_depth = frame.setup().close_depth;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const float z = frame.depth(i);
    if (z <= 0 || z >= close_depth) continue;
    if (frame.map_point(i) && !frame.is_outlier(i)) {
      ++tracked_close;
    } else {
      ++untracked_close;
    }
  }
  const bool need_close = tracked_close < options_.close_points_tracked_min &&
                          untracked_close > options_.close_points_untracked_min;
  const double ratio = num_keyframes < 2 ? 0.4 : 0.75;

  const bool c1a = since_last >= static_cast<std::uint64_t>(options_.max_frames_between_keyframes);
  const bool c1b = since_last >= static_cast<std::uint64_t>(options_.min_frames_between_keyframes) && idle;
  const bool c1c = inliers < reference_matches * 0.25 || need_close;
  const bool c2 = (inliers < reference_matches * ratio || need_close) && inliers > 15;
  if (!((c1a || c1b || c1c) && c2)) return false;
  const bool weak = inliers < reference_matches * 0.25;
  const bool outside_budget = weak || inliers < options_.keyframe_budget_inliers;
  if (!outside_budget && !keyframe_budget_.allows(frame.timestamp())) return false;
  const std::size_t queued = link_.queued_keyframes ? link_.queued_keyframes(frame.timestamp()) : 0;
  const KeyFrameAdmission admission =
      admit_keyframe(idle, weak, need_close, queued, inliers < options_.interrupt_inliers);
  if (admission.interrupt_bundle_adjustment && link_.interrupt_bundle_adjustment) {
    link_.interrupt_bundle_adjustment();
  }
  return admission.insert;
}

void Tracker::create_keyframe(Frame& frame, bool start_window) {
  // Temporary odometry points never enter keyframes, nor do outlier matches;
  // a keypoint whose match failed the pose check (it moved, or was
  // mismatched) does not become a new depth point either.
  std::vector<bool> failed_match(frame.size(), false);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const MapPointPtr& mp = frame.map_point(i);
    if (!mp) continue;
    if (frame.is_outlier(i)) failed_match[i] = options_.skip_outlier_keypoints || start_window;
    if (mp->num_observations() < 1 || frame.is_outlier(i)) frame.set_map_point(i, nullptr);
  }
  KeyFramePtr kf = map_->create_keyframe(frame);
  std::vector<std::pair<float, std::size_t>> by_depth;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.depth(i) > 0) by_depth.emplace_back(frame.depth(i), i);
  }
  std::sort(by_depth.begin(), by_depth.end());
  int n = 0;
  const double close_depth = frame.setup().close_depth;
  // The previous frame confirms new depth points (tracking/depth_point_check.h)
  // when it directly precedes this one.
  // In the start's window the previous tracked frame checks them however far back it lies.
  const bool check = last_frame_.has_pose() &&
                     ((options_.new_point_check.enabled && last_frame_.id() + 1 == frame.id()) || start_window);
  // Under a carried mask too old, the new points wait for the frame's own mask.
  const bool provisional = makes_provisional_points(frame);
  // Under a carried mask, keypoints near a carried person at its depth are likely on it.
  const std::vector<char> near_person = near_carried_person(frame, options_.near_person);
  for (const auto& [z, i] : by_depth) {
    if (!frame.map_point(i) && !failed_match[i]) {
      if (near_person[i]) {
        ++near_person_skipped_;
        continue;
      }
      const Eigen::Vector3d p = *kf->unproject(i);
      if (check && !seen_where_predicted(last_frame_, p, frame.descriptor(i), options_.new_point_check)) continue;
      MapPointPtr mp = map_->create_map_point(p, kf.get());
      mp->add_observation(kf.get(), i);
      kf->set_map_point(i, mp);
      mp->compute_distinctive_descriptor();
      mp->update_normal_and_depth(frame.setup().pyramid);
      if (provisional) {
        mp->set_provisional();  // the next frame's motion model sees a temporary point there instead
      } else {
        frame.set_map_point(i, mp);
      }
    }
    ++n;
    if (z > close_depth && n > options_.new_keyframe_points) break;
  }
  frame.set_reference_keyframe(kf);
  reference_keyframe_ = kf;
  last_keyframe_ = kf;
  last_keyframe_frame_id_ = frame.id();
  keyframe_budget_.spend(frame.timestamp());
  if (link_.insert_keyframe) link_.insert_keyframe(kf, frame);
}

bool Tracker::makes_provisional_points(const Frame& frame) const {
  return options_.provisional_mask_age >= 0 && frame.mask_age() > options_.provisional_mask_age;
}

}  // namespace stillslam
