#pragma once
// Whether a segmented instance (a person, a car) actually moves: each frame
// its matched features' motion residuals (motion_residual.h) are compared
// with those of the static background in the same frame, so tracking noise,
// blur and depth noise, which raise both, do not count as motion. An instance
// agrees with the camera motion when its median residual stays near the
// background's, and disagrees when it is clearly above it. Agreement is
// accumulated over frames as log-odds; disagreement weighs more than
// agreement (removing a still object costs texture, keeping a moving one
// costs the pose), so one clear motion undoes several frames of stillness.
// An instance is kept as static once the log-odds reach its class's
// evidence (a still person needs more than a parked car).
#include <map>
#include <string>
#include <vector>

namespace stillslam {

struct MotionEvidenceOptions {
  // Agreement: instance median residual <= max(static_factor * background median, static_floor_px).
  double static_factor = 2.0;
  double static_floor_px = 1.5;
  // Disagreement: instance median residual > max(moving_factor * background median, moving_floor_px).
  double moving_factor = 3.0;
  double moving_floor_px = 3.0;
  // The same for objects (instances of classes not masked for their class: a
  // box, a chair), which are masked once they disagree: a lower bar than for
  // people finds a pushed object in the first frames of its motion, and a
  // person's sway never meets it as people are judged with the one above.
  double object_moving_factor = 3.0;
  double object_moving_floor_px = 3.0;
  int min_matches = 4;        // fewer matched features on an instance: no evidence this frame
  // An instance of a masked class (a person) kept as static loses its
  // evidence only to a disagreement from at least kept_min_matches matches
  // with a median residual of at most kept_max_px: fewer matches, or
  // residuals far above a walk's (about 70 px over 6 frames at 2 m), are
  // mismatches on its sway-blurred texture, not motion (bench/README.md,
  // issue #19 session 11). Objects are not shielded.
  int kept_min_matches = 8;
  double kept_max_px = 150.0;
  int min_background = 20;    // fewer background matches: no evidence for anyone this frame
  double moving_weight = 4.0; // log-odds lost per disagreeing frame (one agreeing frame gains 1)
  // Agreeing frames an instance needs before it is kept as static (its
  // "evidence window"), per class name; classes not listed use default_frames.
  int default_frames = 10;
  std::map<std::string, int> frames_by_class;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
  int frames_for(const std::string& category) const;
};

enum class MotionVerdict { NoEvidence, Agrees, Disagrees };

struct InstanceResiduals {
  int id = 0;                      // instance id, stable across frames
  std::string category;            // class name (person, car, ...)
  std::vector<double> residuals;   // of its features matched in both frames, pixels
  bool object = false;             // judged with the object_moving_* bar
};

struct InstanceMotionState {
  int id = 0;
  MotionVerdict verdict = MotionVerdict::NoEvidence;  // this frame
  int matches = 0;
  double median_px = 0;       // this frame (0 without matches)
  double log_odds = 0;        // agreeing frames minus moving_weight per disagreeing one, in [0, class evidence]
  bool is_static = false;     // log_odds reached the class's evidence
};

class MotionEvidence {
 public:
  explicit MotionEvidence(MotionEvidenceOptions options = {});

  // One frame: the residuals of the static background's matched features and
  // of each instance's. Instances not passed keep their state.
  std::vector<InstanceMotionState> update(const std::vector<double>& background,
                                          const std::vector<InstanceResiduals>& instances);
  // The states update() would give for this frame, with nothing changed.
  std::vector<InstanceMotionState> peek(const std::vector<double>& background,
                                        const std::vector<InstanceResiduals>& instances) const;
  // Median background residual of the last update (0 before any).
  double background_median() const { return background_median_; }
  bool is_static(int id) const;
  bool has(int id) const { return states_.count(id) > 0; }
  // Drops an instance that left the view or was lost by the segmenter.
  void forget(int id) { states_.erase(id); }
  std::size_t tracked() const { return states_.size(); }

 private:
  MotionEvidenceOptions options_;
  std::map<int, InstanceMotionState> states_;
  double background_median_ = 0;
};

// Median of the values (0 when empty); the vector is reordered.
double median_of(std::vector<double>& values);

}  // namespace stillslam
