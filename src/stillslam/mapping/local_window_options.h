#pragma once
// Budget of the local BA window (mapping/local_bundle_adjustment.h): how many
// keyframes, points and observations one local BA may take, so its cost is
// bounded whatever the covisibility graph looks like (a camera circling a
// room sees most keyframes from each one). 0 means no limit. Defaults from
// bench/README.md (2026-12-02): 12 + 8 keyframes lost accuracy on the demo.
namespace stillslam {

struct LocalWindowOptions {
  // Free keyframes: the new one, then its covisibles by decreasing weight.
  int max_keyframes = 20;
  // Fixed keyframes (observers of window points outside it), those with the
  // most window observations first; the others' observations are left out.
  int max_fixed_keyframes = 10;
  // Points, taken keyframe by keyframe in the order above.
  int max_points = 3000;
  // Observations (each point counted with all its observations, so the
  // window never exceeds it).
  int max_observations = 20000;
  // Points flagged as seen on a person kept as static
  // (MapPoint::on_dynamic_instance) stay out of the window: they neither
  // move nor pull its keyframes (System sets it from Motion.enabled and
  // Motion.keptPointsOutOfBA; not a LocalMapping.* key).
  bool leave_out_kept_points = false;
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

}  // namespace stillslam
