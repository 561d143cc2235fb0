#pragma once
// How many keyframes tracking may hand to local mapping per second of input
// (issue #21): each keyframe costs the mapper tens of CPU-ms (registration,
// triangulation, fusion, local BA), and on 2 cores at 30 Hz it cannot take one
// every frame. A token bucket on the frames' timestamps, so deterministic and
// threaded runs make the same decision: it fills at per_second and holds at
// most `burst` keyframes; an ordinary keyframe needs a whole token. Tracking
// about to fail, or with few inliers (TrackerOptions::keyframe_budget_inliers),
// takes its keyframe anyway (the balance stays at >= 0). The first
// `start_keyframes` keyframes of a map are outside the budget: a young map
// needs them (a 40-frame sequence lost half its accuracy without them), and
// the bucket is full after them. With `start_seconds` > 0 that exemption also
// ends that many seconds after the map's first keyframe.
namespace stillslam {

struct KeyFrameBudgetOptions {
  double per_second = 6;  // 0: no budget; 6: bench/README.md, issue #21 session 15
  double burst = 2;       // keyframes that may come back to back
  int start_keyframes = 10;  // a map's first keyframes, outside the budget (bench/README.md, issue #21 session 11)
  double start_seconds = 0;  // ...and only within this many seconds of the map's first keyframe (0: no limit)
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

class KeyFrameBudget {
 public:
  explicit KeyFrameBudget(KeyFrameBudgetOptions options = {});
  // A keyframe at `timestamp` (seconds) is within the budget.
  bool allows(double timestamp) const;
  // A keyframe was made at `timestamp`.
  void spend(double timestamp);
  // Full again (a new map).
  void reset();

 private:
  double balance_at(double timestamp) const;
  bool in_start(double timestamp) const;

  KeyFrameBudgetOptions options_;
  double balance_ = 0;
  double last_timestamp_ = 0;
  bool started_ = false;  // no keyframe in the budget yet: full
  int keyframes_ = 0;     // made since the start or the last reset
  double first_timestamp_ = 0;  // of the map's first keyframe (keyframes_ > 0)
};

}  // namespace stillslam
