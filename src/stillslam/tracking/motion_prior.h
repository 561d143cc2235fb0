#pragma once
// The constant-velocity prediction as a prior on the pose stages (issue #20).
// A close thing that earned static evidence while it stood still and then
// walks off drags the evidence pose along the weakly fixed directions (the
// far static points stay inside their chi2 bounds at the moved pose). The
// motion model's prediction, weighted by optimize/pose_prior.h, holds those
// directions. With a gate the prior is used only in a stage whose pose
// without it lands farther than the gate from the prediction.
#include <optional>

#include "stillslam/map/frame.h"
#include "stillslam/optimize/pose_prior.h"
#include "stillslam/tracking/static_evidence.h"

namespace stillslam {

struct MotionPriorOptions {
  // Tracking.motionPriorSigma: m, on the camera centre; 0: no prior. 1 mm
  // with the 2 cm gate and the refit check: --no-segmentation wx 0.37 m ->
  // 5 mm (RGB-D), n1 stereo 0.21 -> 0.048 m, stereo twins 0.97-1.00x
  // (bench/README.md, session 9).
  double sigma_translation = 0.001;
  // Tracking.motionPriorRotationSigma: rad.
  double sigma_rotation = 0.01;
  // Tracking.motionPriorDeadZone: m; camera-centre offsets from the
  // prediction up to this cost nothing.
  double dead_zone = 0;
  // Tracking.motionPriorGate: m. > 0: a stage's pose is first estimated
  // without the prior, and again with it only when that pose's camera
  // centre lies farther than this from the prediction. 0: always the prior.
  // A constant-velocity prediction at 30 Hz is off by a few mm on a hand-held
  // path; a capture jumps centimetres in one frame.
  double gate = 0.02;
  // Tracking.motionPriorRefit: with the gate, the pose with the prior is kept
  // only when the points it keeps as inliers, fitted again without the
  // prior, stay within the gate of the prediction: the pose left the
  // prediction because of the points the prior rejects (a thing that moves),
  // not because the points as a whole disagree with it. On stereo the raw
  // frame poses jitter by mm, and a constant-velocity prediction from two of
  // them lands 2-4 cm off on static scenes (bench/README.md, session 9).
  bool refit = true;
  bool enabled() const { return sigma_translation > 0; }
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

// The prior around `predicted` (the motion model's pose for this frame);
// nullopt when the options are off.
std::optional<PosePrior> motion_prior(const Eigen::Isometry3d& predicted, const MotionPriorOptions& options);

// What the prior did in one pose stage (for stats.json and the benches).
struct MotionPriorStep {
  bool applied = false;  // the returned pose used the prior
  // m: camera centre of the pose without the prior from the prediction
  // (-1 when the gate did not look: no prior, or gate 0).
  double offset = -1;
  // Share of the inliers of the pose without the prior that the pose with it
  // rejects (-1: the prior pose was not computed).
  double rejected_share = -1;
  // m: camera centre of the refit from the prediction (-1: no refit).
  double refit_offset = -1;
};

// A frame's pose stages together: how many used the prior, and the largest
// of each figure (-1: no stage had it).
struct MotionPriorFrame {
  int applied = 0;
  double offset = -1;
  double rejected_share = -1;
  double refit_offset = -1;
  void add(const MotionPriorStep& step);
};

// refine_pose_on_evidence (static_evidence.h) with the prior and its gate;
// without a prior it is refine_pose_on_evidence. `step` (optional) tells
// what the gate saw; `start` (optional) is passed on to
// refine_pose_on_evidence. Returns the number of inliers.
int refine_pose_with_prior(Frame& frame, const PoseOptimizerOptions& pose, const StaticEvidenceOptions& evidence,
                           const std::optional<PosePrior>& prior, const MotionPriorOptions& options,
                           MotionPriorStep* step = nullptr, const StartEvidence* start = nullptr);

}  // namespace stillslam
