#include "stillslam/segmentation/async_masks.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "stillslam/core/option_check.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/segmentation/mask_grow.h"

namespace stillslam {

void AsyncMaskOptions::check() const {
  using namespace option_check;
  at_least("SegmentationOptions.interval", interval, 1);
  at_least("SegmentationOptions.max_mask_age", max_mask_age, 0);
  at_least("SegmentationOptions.modelled_latency", modelled_latency, 0);
  at_least("AsyncMaskOptions.grow_px_per_frame", grow_px_per_frame, 0);
  at_least("SegmentationOptions.max_grow_px", max_grow_px, 0);
  if (modelled_latency > max_mask_age) {
    throw OptionError("SegmentationOptions.modelled_latency", text(modelled_latency),
                      "must be at most max_mask_age (" + text(max_mask_age) + ")");
  }
}

AsyncMaskOptions AsyncMaskOptions::from(const SegmentationOptions& segmentation) {
  AsyncMaskOptions o;
  o.interval = segmentation.interval;
  o.max_mask_age = segmentation.max_mask_age;
  o.modelled_latency = segmentation.modelled_latency;
  o.max_grow_px = segmentation.max_grow_px;
  return o;
}

AsyncMasks::AsyncMasks(SegmentationStage& stage, AsyncMaskOptions options, std::optional<MaskPropagator> propagator,
                       int dilation_px)
    : stage_(stage),
      options_(options),
      scheduler_((options.check(), options.interval)),
      propagator_(std::move(propagator)),
      dilation_px_(dilation_px) {}

void AsyncMasks::on_tracked(std::size_t frame_index, const std::optional<Eigen::Isometry3d>& T_cam_world,
                            cv::Mat1f sparse_depth) {
  auto kept = submitted_.find(frame_index);
  if (kept != submitted_.end()) {
    kept->second.T_cam_world = T_cam_world;
    if (kept->second.depth.empty()) kept->second.depth = std::move(sparse_depth);
  }
  if (!T_cam_world) {
    poses_.clear();
    return;
  }
  if (propagator_ && last_propagated_ == frame_index && !propagator_->empty()) propagator_->set_last_pose(*T_cam_world);
  poses_.emplace_back(frame_index, *T_cam_world);
  if (poses_.size() > 2) poses_.pop_front();
}

bool AsyncMasks::wants_sparse_depth(std::size_t frame_index) const {
  const auto kept = submitted_.find(frame_index);
  return kept != submitted_.end() && kept->second.depth.empty();
}

std::optional<Eigen::Isometry3d> AsyncMasks::predicted_pose(std::size_t frame_index) const {
  // Constant velocity over consecutive tracked frames; none across gaps.
  if (poses_.size() < 2 || poses_[1].first + 1 != frame_index || poses_[0].first + 1 != poses_[1].first) {
    return std::nullopt;
  }
  return poses_[1].second * poses_[0].second.inverse() * poses_[1].second;
}

cv::Mat1b AsyncMasks::propagated(std::size_t frame_index, const cv::Mat1b& gray, const cv::Mat1f& depth, int age,
                                 std::vector<PropagatedInstance>& instances) {
  if (reset_from_ != fresh_->frame_index) {
    const auto kept = submitted_.find(fresh_->frame_index);
    if (kept == submitted_.end()) return carried(*fresh_, age);
    SegmentedFrame fresh;
    fresh.frame_id = fresh_->frame_index;
    fresh.gray = kept->second.gray;
    fresh.depth = kept->second.depth;
    fresh.right = kept->second.right;
    fresh.instances = fresh_->instances;
    // Instances the segmenter lost (MaskHold) move like the others: with the
    // camera and their own flow, not left where they were in the image.
    fresh.instances.insert(fresh.instances.end(), fresh_->held_instances.begin(), fresh_->held_instances.end());
    fresh.T_cam_world = kept->second.T_cam_world;
    propagator_->reset(std::move(fresh));
    reset_from_ = fresh_->frame_index;
    last_propagated_ = fresh_->frame_index;
  }
  if (age == 0) return fresh_->dynamic_mask;
  PropagatedMasks moved = propagator_->propagate(frame_index, gray, depth, predicted_pose(frame_index));
  last_propagated_ = frame_index;
  instances = std::move(moved.instances);
  // A disc like the fresh masks' dilation, computed only around the mask
  // (grow_mask), not over the whole frame.
  return grow_mask(moved.union_mask, dilation_px_);
}

bool AsyncMasks::stage_busy() const { return stage_.threaded() ? stage_.busy() : !pending_.empty(); }

void AsyncMasks::submit(const cv::Mat& bgr, std::size_t frame_index) {
  ordinals_[frame_index] = processed_ - 1;  // mask_for() counted this frame already
  if (propagator_ && !pending_gray_.empty()) {
    submitted_[frame_index] = Submitted{pending_gray_, pending_depth_, std::nullopt, pending_right_};
  }
  stage_.submit(bgr, frame_index);
  if (!stage_.threaded()) pending_.push_back(stage_.latest());
}

std::size_t AsyncMasks::ordinal_of(std::size_t frame_index) const {
  const auto it = ordinals_.find(frame_index);
  return it != ordinals_.end() ? it->second : processed_ - 1;  // every result is of a submitted frame
}

void AsyncMasks::collect(std::size_t ordinal) {
  if (stage_.threaded()) {
    std::shared_ptr<const SegmentationResult> r = stage_.latest();
    if (r && (!fresh_ || r->frame_index > fresh_->frame_index)) fresh_ = std::move(r);
    return;
  }
  const auto latency = static_cast<std::size_t>(options_.modelled_latency);
  while (!pending_.empty() && ordinal_of(pending_.front()->frame_index) + latency <= ordinal) {
    fresh_ = pending_.front();
    pending_.pop_front();
  }
}

void AsyncMasks::wait_for(std::size_t frame_index) {
  if (stage_.threaded()) {
    fresh_ = stage_.wait_for(frame_index);
    return;
  }
  while (!pending_.empty() && pending_.front()->frame_index <= frame_index) {
    fresh_ = pending_.front();
    pending_.pop_front();
  }
}

bool AsyncMasks::segment_last(const cv::Mat& bgr, std::size_t frame_index) {
  needed_ = frame_index;
  const std::optional<std::size_t> last = stage_.last_submitted();
  if (last && *last == frame_index) return false;
  scheduler_.record_request(processed_ - 1);
  submit(bgr, frame_index);
  return true;
}

cv::Mat1b AsyncMasks::carried(const SegmentationResult& result, int age) const {
  const int grow = std::min(age * options_.grow_px_per_frame, options_.max_grow_px);
  if (age == 0 || grow == 0 || result.dynamic_mask.empty() || cv::countNonZero(result.dynamic_mask) == 0) {
    return result.dynamic_mask;
  }
  cv::Mat1b out;
  // A square kernel: cheap at any size, and covers motion in any direction.
  cv::dilate(result.dynamic_mask, out, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * grow + 1, 2 * grow + 1)));
  return out;
}

FrameMask AsyncMasks::mask_for(const cv::Mat& bgr, std::size_t frame_index, const cv::Mat& gray,
                               const cv::Mat& depth, const cv::Mat& right) {
  FrameMask out;
  pending_gray_ = gray;
  pending_depth_ = depth;
  pending_right_ = right;
  const std::size_t ordinal = processed_++;
  collect(ordinal);
  if (needed_ && fresh_ && fresh_->frame_index >= *needed_) needed_.reset();
  // A held keyframe's request must not be replaced before the stage takes it.
  if (!needed_ || !stage_busy()) out.scheduled = scheduler_.decide(ordinal, stage_busy());
  if (out.scheduled != ScheduleReason::None) submit(bgr, frame_index);
  collect(ordinal);  // deterministic with no latency: this frame's own result

  const auto max_age = static_cast<std::size_t>(options_.max_mask_age);
  if (!fresh_ || ordinal - ordinal_of(fresh_->frame_index) > max_age) {
    Stopwatch wait;
    // The request in flight if its mask would be young enough, else this frame's own.
    const std::optional<std::size_t> last = stage_.last_submitted();
    const bool in_flight = last && (!fresh_ || *last > fresh_->frame_index);
    std::size_t target = frame_index;
    if (in_flight && ordinal - ordinal_of(*last) <= max_age) {
      target = *last;
    } else {
      scheduler_.record_request(ordinal);
      out.scheduled = ScheduleReason::Waiting;
      submit(bgr, frame_index);
    }
    wait_for(target);
    out.waited = true;
    out.wait_ms = wait.elapsed_ms();
  }
  out.source = fresh_;
  out.age = static_cast<int>(ordinal - ordinal_of(fresh_->frame_index));
  out.input_age = static_cast<int>(frame_index - fresh_->frame_index);
  ThreadCpuStopwatch carrying;
  if (propagator_ && !gray.empty()) {
    out.mask = propagated(frame_index, pending_gray_, pending_depth_, out.input_age, out.instances);
    // What a later fresh result could start from is kept; older frames are not needed.
    submitted_.erase(submitted_.begin(), submitted_.lower_bound(fresh_->frame_index));
  } else {
    // People move with time: a mask grows by input frames (dropped ones too).
    out.mask = carried(*fresh_, out.input_age);
  }
  out.propagation_cpu_ms = carrying.elapsed_ms();
  ordinals_.erase(ordinals_.begin(), ordinals_.lower_bound(fresh_->frame_index));
  return out;
}

}  // namespace stillslam
