#pragma once
// How long local mapping would be busy with each keyframe (issue #21).
// Deterministic runs map synchronously: the mapper is never busy when tracking
// asks, so it took a keyframe at nearly every frame (26 per second on the
// halfsphere sequence against 5.5 threaded). The model charges each processed
// keyframe a cost from its local-BA size,
//   busy_ms = keyframe_ms + observations * (observation_us + iterations * observation_iteration_us) / 1000,
// and queues the keyframes on the input timestamps: one starts when it
// arrives or when the one before it is done, whichever is later. Tracking's
// keyframe admission then asks the model instead of the (always idle) mapper,
// so deterministic runs take keyframes at about the threaded rate.
#include <cstddef>
#include <deque>

namespace stillslam {

struct MapperBusyModelOptions {
  double keyframe_ms = 20;  // registration, triangulation, fusion, culling
  // Kept at the Ceres solver's CPU fit although the Schur solver needs ~4x
  // less: refit to its CPU (1.7, 0.18), deterministic hs took 19.5 keyframes/s
  // against 8.2 threaded; these give 6.9 (bench/README.md, "Issue #21, session 9").
  double observation_us = 6;               // per local-BA observation: gathering, setup, apply
  double observation_iteration_us = 0.75;  // per observation and solver iteration
  // Throws OptionError naming the field, its value and the valid range.
  void check() const;
};

class MapperBusyModel {
 public:
  explicit MapperBusyModel(MapperBusyModelOptions options = {});
  // The modelled cost of one keyframe whose local BA had `observations`
  // observations and ran `iterations` solver iterations (0, 0: no BA).
  double busy_ms(int observations, int iterations) const;
  // A keyframe that arrived at `arrival` (input timestamp, seconds) keeps
  // the mapper busy for `busy_ms`. Arrivals come in order.
  void add(double arrival, double busy_ms);
  // At `now`, no modelled keyframe is in progress or waiting.
  bool idle(double now) const;
  // At `now`, modelled keyframes that arrived but have not started.
  std::size_t queued(double now) const;
  // The input time the mapper is busy until (0 before any keyframe).
  double busy_until() const { return busy_until_; }
  // Forget every keyframe (a new map).
  void reset();

 private:
  MapperBusyModelOptions options_;
  std::deque<double> starts_;  // of the keyframes that may still be waiting
  double busy_until_ = 0;
};

}  // namespace stillslam
