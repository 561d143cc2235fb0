#pragma once
// The tracking state machine (ORB-SLAM style, RGB-D/stereo): initialization
// from one frame with depth, constant-velocity motion model with projection
// search, reference-keyframe fallback, local-map tracking, keyframe decision
// and creation. On loss it first tries relocalization (place recognition,
// wired by System through the link), then searches the last keyframe's local
// map with a wide window.
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/map/frame.h"
#include "stillslam/map/map.h"
#include "stillslam/tracking/keyframe_budget.h"
#include "stillslam/tracking/motion_prior.h"
#include "stillslam/tracking/sparse_view.h"
#include "stillslam/tracking/start_evidence.h"
#include "stillslam/tracking/tracker_options.h"
#include "stillslam/tracking/tracking_state.h"

namespace stillslam {

// How tracking talks to local mapping (wired by System; all optional).
struct LocalMappingLink {
  // A new keyframe and the frame being tracked when it was made: the keyframe
  // is made from that frame, except the first keyframe of a map started from
  // an earlier frame (kf->frame_id() tells).
  std::function<void(KeyFramePtr, const Frame&)> insert_keyframe;
  // Asked with the frame's timestamp (the mapper may model its busy time on it).
  std::function<bool(double)> accepts_keyframes;  // idle
  std::function<std::size_t(double)> queued_keyframes;
  std::function<void()> interrupt_bundle_adjustment;
  // Relocalization while lost, called with the map lock held: on success the
  // frame holds its pose, inlier map-point matches and reference keyframe.
  std::function<bool(Frame&)> relocalize;
};

// A frame the map's start waited on, posed when the map started from an
// earlier frame: the first keyframe's own frame (at the map's origin) or a
// frame that confirmed it (at the start check's PnP motion from it).
struct StartFramePose {
  // The frame with its pose and, as its map points, the first keyframe's
  // points its confirmed matches saw (none for the first keyframe's frame).
  Frame frame;
  KeyFramePtr reference;  // the map's first keyframe
  Eigen::Isometry3d T_cam_reference = Eigen::Isometry3d::Identity();
  bool keyframe = false;  // the first keyframe was made from this frame
};

struct TrackingResult {
  TrackingState state = TrackingState::NotInitialized;
  std::string reason;  // why not Ok, or which method succeeded
  int matches = 0;     // matched map points before the final optimization
  int inliers = 0;     // map-point inliers after it
  bool new_keyframe = false;
  // A keyframe was due but the frame's mask was too old (max_keyframe_mask_age).
  bool keyframe_deferred = false;
  bool relocalized = false;  // recovered from Lost by relocalization (reason "relocalized")
  SparseView sparse_view = SparseView::None;  // the crowd fallback's action (tracking/sparse_view.h)
  // The directions (world axes) along which the centre filter moved this
  // frame's centre (SparseViewOptions::filter_axes); identity otherwise.
  Eigen::Matrix3d sparse_filter_projection = Eigen::Matrix3d::Identity();
  MotionPriorFrame motion_prior;  // the motion prior in this frame's pose stages (tracking/motion_prior.h)
  // When Ok: the frame's reference keyframe and its pose relative to it, taken
  // under the map lock (local BA may move the keyframe right after).
  KeyFramePtr reference;
  Eigen::Isometry3d T_cam_reference = Eigen::Isometry3d::Identity();
  // When this frame started the map from an earlier one: the frames the start
  // waited on before this one, oldest first (they had no pose when tracked).
  std::vector<StartFramePose> start_frames;
};

class Tracker {
 public:
  Tracker(Map& map, TrackerOptions options, LocalMappingLink link);

  // Tracks one frame (takes the map's update mutex). On success the frame
  // holds its pose and reference keyframe.
  TrackingResult track(Frame& frame);

  // Atlas: forget everything and initialize a new (empty) map from the next
  // frame with enough depth. The old map is no longer touched.
  void start_new_map(Map& map);
  // Atlas merge: the tracker's keyframes now live in `map` (moved there with
  // corrected poses); tracking continues without a break.
  void switch_map(Map& map);
  // A map that already has keyframes (a loaded one): forget the current
  // state and start lost, so the next frames relocalize in it and then track.
  void localize_in(Map& map);
  Map& map() const { return *map_; }
  // A keyframe made from `frame` makes its new depth points provisional
  // (TrackerOptions::provisional_mask_age): the rule create_keyframe applies,
  // for System to know which keyframes wait for their own mask.
  bool makes_provisional_points(const Frame& frame) const;

  TrackingState state() const { return state_; }
  // The next frame's pose as the motion model predicts it from the last
  // tracked frame (its velocity, else the last pose itself); none while not
  // tracking.
  std::optional<Eigen::Isometry3d> predicted_pose() const;
  // While no map is started: the frame the first keyframe would be made from
  // if the next frames confirm it (Tracker options init_confirm_frames).
  std::optional<std::uint64_t> start_candidate_id() const {
    return start_candidate_ ? std::optional<std::uint64_t>(start_candidate_->id()) : std::nullopt;
  }
  const KeyFramePtr& last_keyframe() const { return last_keyframe_; }
  // Keypoints that made no depth point in a keyframe because they lay near a
  // carried person at its depth (TrackerOptions::near_person), in all.
  std::size_t near_person_skipped() const { return near_person_skipped_; }

 private:
  enum class Start { Waiting, FromThisFrame, FromAnEarlierFrame };
  // Starts the map from an earlier frame that this frame confirms (or, with
  // no check, from this frame); sets the reason while waiting.
  Start try_to_start_map(Frame& frame, TrackingResult& result);
  // keep: per keypoint, may become a map point (empty: all).
  // The first keyframe, from `frame`, while `tracked` (the same or a later frame) is tracked.
  void initialize(Frame& frame, const Frame& tracked, const std::vector<bool>& keep = {});
  bool track_with_motion_model(Frame& frame, TrackingResult& result);
  bool track_reference_keyframe(Frame& frame, TrackingResult& result);
  bool track_while_lost(Frame& frame, TrackingResult& result);
  bool track_local_map(Frame& frame, TrackingResult& result);
  // The crowd fallback (tracking/sparse_view.h): true when no map may start
  // from this frame; after tracking, the pose of a sparse view (returns
  // whether the frame has one).
  bool refuse_sparse_start(const Frame& frame, TrackingResult& result);
  // Of the start candidate's points the confirming frames matched so far: how many, and how many some frame found moving.
  std::pair<int, int> start_tally() const;
  // Forgets the start candidate and the frames that confirmed it; returns a
  // note naming the frames that so get no pose (empty when there was none).
  std::string drop_start_candidate();
  // The start candidate's frame and the confirming frames before `frame`,
  // posed in the map just started from the candidate (`first`, now its first keyframe).
  std::vector<StartFramePose> pose_start_frames(Frame first);
  bool sparse_view_fallback(Frame& frame, TrackingResult& result, bool ok);
  int search_points(Frame& frame, const std::vector<MapPointPtr>& points, float th);
  void update_last_frame();
  KeyFrame* anchor_keyframe() const;
  void cull_outlier_streaks(const Frame& frame, int inliers);
  // The motion-model and local-map pose stages: the evidence pose with this
  // frame's motion prior (tracking/motion_prior.h), if any.
  int refine_stage_pose(Frame& frame, TrackingResult& result);
  // SparseViewOptions::filter_gain on a tracked sparse view: its centre
  // filtered, its pose re-estimated from its inliers with the centre held.
  void filter_sparse_centre(Frame& frame, TrackingResult& result);
  // SparseViewOptions::keyframe_prior_sigma: the centre prior of a keyframe
  // made from this tracked sparse view (its inliers give the directions).
  KeyFrame::CentrePrior sparse_keyframe_prior(const Frame& frame) const;
  bool need_new_keyframe(const Frame& frame, int inliers) const;
  // In the start's trust window (start_evidence_), new depth points only where
  // the match was not rejected and the previous frame saw the point in place.
  void create_keyframe(Frame& frame, bool start_window = false);

  Map* map_;  // never null
  TrackerOptions options_;
  LocalMappingLink link_;
  TrackingState state_ = TrackingState::NotInitialized;
  Frame last_frame_;
  // The last frame's pose relative to its reference keyframe, so that map
  // corrections of that keyframe carry over to the motion prediction.
  Eigen::Isometry3d T_last_ref_ = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> velocity_;  // T_cur_last of the last step
  std::optional<PosePrior> motion_prior_;      // this frame's, set by the motion-model stage
  // The last frames' poses through their reference keyframes, oldest first
  // (SparseViewOptions::filter_frames + 1 of them at most, with the filter
  // on); cleared with the velocity.
  struct PastPose {
    std::uint64_t frame_id = 0;
    KeyFramePtr reference;
    Eigen::Isometry3d T_cam_reference = Eigen::Isometry3d::Identity();
  };
  std::deque<PastPose> past_poses_;
  CentreFilter centre_filter_;  // SparseViewOptions::filter_gain
  KeyFramePtr reference_keyframe_;
  KeyFramePtr last_keyframe_;
  std::uint64_t last_keyframe_frame_id_ = 0;
  KeyFrameBudget keyframe_budget_;
  std::uint64_t last_lost_frame_id_ = 0;
  bool was_lost_ = false;
  std::uint64_t temporary_point_id_ = 0;
  std::size_t near_person_skipped_ = 0;
  // The first keyframe awaiting confirmation by the next frames, with the
  // keypoints that may become map points.
  std::optional<Frame> start_candidate_;
  std::vector<bool> start_keep_;
  std::vector<bool> start_confirmed_;  // matched as an inlier by some confirming frame
  std::vector<bool> start_matched_;    // matched (with depth) by some confirming frame
  // Keypoints of last_frame_ that give no visual-odometry point (the map's
  // first frame: those its start check left out).
  std::vector<bool> last_frame_left_out_;
  // The frames that confirmed the start candidate so far (before the one
  // that starts the map), each with its pose relative to the candidate (the
  // check's PnP motion) and, per candidate keypoint, its confirmed match (-1: none).
  struct ConfirmingFrame {
    Frame frame;
    std::vector<int> candidate_matches;
  };
  std::vector<ConfirmingFrame> start_confirming_;
  int start_confirmations_ = 0;
  int start_frames_rejected_ = 0;  // frames that had the depth but failed the check
  int start_gap_frames_ = 1;  // frames between the first keyframe and the frame that started the map
  // After a start checked without masks: its checked points as evidence (tracking/start_evidence.h).
  StartEvidence start_evidence_;
};

}  // namespace stillslam
