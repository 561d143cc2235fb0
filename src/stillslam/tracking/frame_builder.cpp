#include "stillslam/tracking/frame_builder.h"

#include <future>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/segmentation/dynamic_mask.h"
#include "stillslam/core/thread_cpu_stopwatch.h"
#include "stillslam/tracking/motion_stage.h"

namespace stillslam {

namespace {

OrbFeatures select(const OrbFeatures& features, const std::vector<std::size_t>& keep) {
  OrbFeatures out;
  out.keypoints.reserve(keep.size());
  out.descriptors.create(static_cast<int>(keep.size()), features.descriptors.cols, features.descriptors.type());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    out.keypoints.push_back(features.keypoints[keep[k]]);
    features.descriptors.row(static_cast<int>(keep[k])).copyTo(out.descriptors.row(static_cast<int>(k)));
  }
  return out;
}

// Leaves out the keypoints inside `mask`; their positions go to `removed`
// when given. Returns how many were left out.
std::size_t drop_keypoints_in(OrbFeatures& features, const cv::Mat1b& mask, std::vector<cv::Point2f>* removed) {
  const std::vector<std::size_t> keep = keypoints_outside_mask(features.keypoints, mask);
  const std::size_t dropped = features.size() - keep.size();
  if (dropped == 0) return 0;
  if (removed) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < features.size(); ++i) {
      if (k < keep.size() && keep[k] == i) {
        ++k;
      } else {
        removed->push_back(features.keypoints[i].pt);
      }
    }
  }
  features = select(features, keep);
  return dropped;
}

}  // namespace

FrameBuilder::FrameBuilder(std::shared_ptr<const CameraSetup> setup, SensorType sensor, const OrbOptions& orb,
                           SegmentationWorker* segmentation, StereoMatchOptions stereo_options)
    : setup_(std::move(setup)),
      sensor_(sensor),
      extractor_(orb),
      segmentation_(segmentation),
      stereo_options_(stereo_options) {
  stereo_options_.check();
}

FrameBuilder::FrameBuilder(std::shared_ptr<const CameraSetup> setup, SensorType sensor, const OrbOptions& orb,
                           AsyncMasks* async_segmentation, StereoMatchOptions stereo_options)
    : FrameBuilder(std::move(setup), sensor, orb, static_cast<SegmentationWorker*>(nullptr), stereo_options) {
  async_ = async_segmentation;
}

Frame FrameBuilder::build(const SensorFrame& input, std::uint64_t frame_id, FrameBuildStats* stats,
                          FrameDynamics* dynamics) const {
  Stopwatch total;
  FrameBuildStats local;
  FrameBuildStats& st = stats ? *stats : local;
  st = FrameBuildStats{};
  if (dynamics) *dynamics = FrameDynamics{};
  if (input.gray.empty()) throw Error("frame " + input.name + ": no grey image to extract features from");
  const bool stereo = sensor_ == SensorType::Stereo;
  if (stereo && input.right.empty()) throw Error("frame " + input.name + ": stereo sensor but no right image");
  if (sensor_ == SensorType::Rgbd && input.depth.empty()) {
    throw Error("frame " + input.name + ": RGB-D sensor but no depth image");
  }

  // 1. Segmentation starts first, on its own thread.
  cv::Mat color = input.color;
  if (color.empty() && segmentation_enabled()) cv::cvtColor(input.gray, color, cv::COLOR_GRAY2BGR);
  std::future<SegmentationResult> mask_future;
  if (segmentation_ != nullptr) mask_future = segmentation_->submit(color, input.index);

  // 2. ORB on the right image (second core) starts at once. The left image
  // waits for the dynamic mask and is extracted outside it, so its whole
  // feature budget goes to the static part of the view.
  std::vector<cv::Mat> left_pyramid, right_pyramid;
  std::future<OrbFeatures> right_future;
  if (stereo) {
    right_future = std::async(std::launch::async, [&] { return extractor_.extract(input.right, &right_pyramid); });
  }
  cv::Mat1b exclude;
  std::vector<CarriedInstance> carried;
  if (segmentation_ != nullptr) {
    Stopwatch wait;
    SegmentationResult seg = mask_future.get();
    st.segmentation_wait_ms = wait.elapsed_ms();
    st.segmentation_ms = seg.time_ms;
    st.segmentation_cpu_ms = seg.cpu_ms;
    st.detections = static_cast<int>(seg.detections.size());
    st.mask_coverage = seg.coverage;
    st.held_coverage = seg.held_coverage;
    exclude = motion_ ? motion_->mask_for(seg.detections, seg.held_mask, color.size()) : std::move(seg.dynamic_mask);
    st.mask_age = 0;
    st.mask_waited = true;
    if (dynamics) dynamics->detections = std::move(seg.detections);
  } else if (async_ != nullptr) {
    // Waits only when the newest mask is too old (async_masks.h).
    const FrameMask m = async_->mask_for(color, input.index, input.gray, input.depth, input.right);
    st.segmentation_wait_ms = m.wait_ms;
    st.propagation_cpu_ms = m.propagation_cpu_ms;
    st.segmentation_ms = m.age == 0 ? m.source->time_ms : 0;
    st.segmentation_cpu_ms = m.age == 0 ? m.source->cpu_ms : 0;
    st.detections = static_cast<int>(m.source->detections.size());
    st.mask_coverage = m.age == 0 ? m.source->coverage : mask_coverage(m.mask);
    st.held_coverage = m.source->held_coverage;
    st.mask_age = m.age;
    st.mask_waited = m.waited;
    st.segmentation_request = m.scheduled;
    st.segmentation_skips = async_->skipped();
    exclude = motion_ && m.age == 0 ? motion_->mask_for(m.source->detections, m.source->held_mask, color.size())
                                    : m.mask;
    if (dynamics) dynamics->detections = m.source->detections;
    for (const PropagatedInstance& inst : m.instances) carried.push_back(CarriedInstance{inst.mask, inst.depth});
  }
  Stopwatch extraction;
  ThreadCpuStopwatch extraction_cpu;
  std::vector<cv::Point2f> removed_here;
  std::vector<cv::Point2f>* removed = dynamics ? &dynamics->removed_keypoints : motion_ ? &removed_here : nullptr;
  // Motion.keptFeatures: the frame's features outside the kept people too, theirs from a budget of their own.
  const cv::Mat1b own_extraction = motion_ ? motion_->extraction_mask() : cv::Mat1b();
  OrbFeatures left = extractor_.extract(input.gray, own_extraction.empty() ? exclude : own_extraction,
                                        stereo ? &left_pyramid : nullptr, removed);
  if (!own_extraction.empty()) {
    OrbFeatures kept = motion_->kept_features(input.gray);
    if (!kept.empty()) {
      left.keypoints.insert(left.keypoints.end(), kept.keypoints.begin(), kept.keypoints.end());
      if (left.descriptors.empty()) {
        left.descriptors = kept.descriptors;
      } else {
        cv::vconcat(left.descriptors, kept.descriptors, left.descriptors);
      }
    }
  }
  st.extraction_cpu_ms = extraction_cpu.elapsed_ms();
  OrbFeatures right;
  if (stereo) right = right_future.get();
  st.extraction_ms = extraction.elapsed_ms();
  st.keypoints_before = static_cast<int>(left.size());

  // 3. Dynamic filter before anything else looks at the keypoints (a guard:
  // the extractor already kept none in the mask).
  if (!exclude.empty()) drop_keypoints_in(left, exclude, dynamics ? &dynamics->removed_keypoints : nullptr);
  st.keypoints_after = static_cast<int>(left.size());
  if (motion_) {
    motion_->collect(input.gray, sensor_ == SensorType::Rgbd ? input.depth : cv::Mat(), exclude, left.keypoints,
                     *removed, st.motion);
    // Motion.predictedCheck: objects found moving at the predicted pose lose their features in this frame.
    const cv::Mat1b moving = motion_->judge_predicted(left.keypoints, left.descriptors, st.motion);
    if (!moving.empty()) {
      st.motion.features_removed_by_motion += static_cast<int>(drop_keypoints_in(left, moving, removed));
      if (exclude.empty()) {
        exclude = moving;
      } else {
        cv::bitwise_or(exclude, moving, exclude);
      }
      st.keypoints_after = static_cast<int>(left.size());
    }
  }

  // 4. Undistortion and depth association.
  Stopwatch association;
  std::vector<cv::KeyPoint> undistorted = setup_->camera.undistort(left.keypoints);
  std::vector<float> u_right(left.size(), -1.f), depth(left.size(), -1.f);
  if (stereo) {
    StereoMatches m = match_stereo(left, left_pyramid, right, right_pyramid, setup_->pyramid, setup_->camera.fx(),
                                   setup_->camera.bf(), stereo_options_);
    u_right = std::move(m.u_right);
    depth = std::move(m.depth);
  } else if (sensor_ == SensorType::Rgbd) {
    StereoMatches m = stereo_from_depth(left.keypoints, undistorted, input.depth, setup_->camera.bf());
    u_right = std::move(m.u_right);
    depth = std::move(m.depth);
  }
  st.association_ms = association.elapsed_ms();

  Frame frame(frame_id, input.timestamp, setup_, std::move(left.keypoints), std::move(undistorted),
              std::move(left.descriptors), std::move(u_right), std::move(depth));
  frame.set_dynamic_mask(exclude);
  frame.set_mask_age(st.mask_age);
  frame.set_carried_instances(std::move(carried));
  st.keypoints_with_depth = frame.num_with_depth();
  st.total_ms = total.elapsed_ms();
  return frame;
}

}  // namespace stillslam
