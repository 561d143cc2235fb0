#include "stillslam/tracking/keyframe_admission.h"

namespace stillslam {

KeyFrameAdmission admit_keyframe(bool mapper_idle, bool tracking_weak, bool need_close, std::size_t queued,
                                 bool urgent) {
  if (mapper_idle) return {true, false};
  if (tracking_weak) return {queued < 3, urgent && queued >= 1};
  return {need_close && queued == 0, false};
}

}  // namespace stillslam
