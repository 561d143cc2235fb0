#pragma once
// Keyframes are keyed by id (not by address) in every ordered container so
// that iteration order, and hence the whole system, is deterministic.
namespace stillslam {

class KeyFrame;

struct KeyFrameIdLess {
  using is_transparent = void;  // lookups with const KeyFrame*
  bool operator()(const KeyFrame* a, const KeyFrame* b) const;
};

}  // namespace stillslam
