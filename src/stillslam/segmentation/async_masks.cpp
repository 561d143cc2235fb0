#include "stillslam/segmentation/async_masks.h"

#include <opencv2/imgproc.hpp>

#include "stillslam/core/option_check.h"
#include "stillslam/core/stopwatch.h"

namespace stillslam {

void AsyncMaskOptions::check() const {
  using namespace option_check;
  at_least("SegmentationOptions.interval", interval, 1);
  at_least("SegmentationOptions.max_mask_age", max_mask_age, 0);
  at_least("SegmentationOptions.modelled_latency", modelled_latency, 0);
  at_least("AsyncMaskOptions.grow_px_per_frame", grow_px_per_frame, 0);
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
  return o;
}

AsyncMasks::AsyncMasks(SegmentationStage& stage, AsyncMaskOptions options)
    : stage_(stage), options_(options), scheduler_((options.check(), options.interval)) {}

bool AsyncMasks::stage_busy() const { return stage_.threaded() ? stage_.busy() : !pending_.empty(); }

void AsyncMasks::submit(const cv::Mat& bgr, std::size_t frame_index) {
  stage_.submit(bgr, frame_index);
  if (!stage_.threaded()) pending_.push_back(stage_.latest());
}

void AsyncMasks::collect(std::size_t frame_index) {
  if (stage_.threaded()) {
    std::shared_ptr<const SegmentationResult> r = stage_.latest();
    if (r && (!fresh_ || r->frame_index > fresh_->frame_index)) fresh_ = std::move(r);
    return;
  }
  const auto latency = static_cast<std::size_t>(options_.modelled_latency);
  while (!pending_.empty() && pending_.front()->frame_index + latency <= frame_index) {
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

cv::Mat1b AsyncMasks::carried(const SegmentationResult& result, int age) const {
  const int grow = age * options_.grow_px_per_frame;
  if (age == 0 || grow == 0 || result.dynamic_mask.empty() || cv::countNonZero(result.dynamic_mask) == 0) {
    return result.dynamic_mask;
  }
  cv::Mat1b out;
  // A square kernel: cheap at any size, and covers motion in any direction.
  cv::dilate(result.dynamic_mask, out, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * grow + 1, 2 * grow + 1)));
  return out;
}

FrameMask AsyncMasks::mask_for(const cv::Mat& bgr, std::size_t frame_index) {
  FrameMask out;
  collect(frame_index);
  out.scheduled = scheduler_.decide(frame_index, stage_busy());
  if (out.scheduled != ScheduleReason::None) submit(bgr, frame_index);
  collect(frame_index);  // deterministic with no latency: this frame's own result

  const auto max_age = static_cast<std::size_t>(options_.max_mask_age);
  if (!fresh_ || frame_index - fresh_->frame_index > max_age) {
    Stopwatch wait;
    // The request in flight if its mask would be young enough, else this frame's own.
    const std::optional<std::size_t> last = stage_.last_submitted();
    const bool in_flight = last && (!fresh_ || *last > fresh_->frame_index);
    std::size_t target = frame_index;
    if (in_flight && frame_index - *last <= max_age) {
      target = *last;
    } else {
      scheduler_.record_request(frame_index);
      out.scheduled = ScheduleReason::Waiting;
      submit(bgr, frame_index);
    }
    wait_for(target);
    out.waited = true;
    out.wait_ms = wait.elapsed_ms();
  }
  out.source = fresh_;
  out.age = static_cast<int>(frame_index - fresh_->frame_index);
  out.mask = carried(*fresh_, out.age);
  return out;
}

}  // namespace stillslam
