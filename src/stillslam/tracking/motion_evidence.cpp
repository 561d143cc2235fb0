#include "stillslam/tracking/motion_evidence.h"

#include <algorithm>

#include "stillslam/core/option_check.h"

namespace stillslam {

void MotionEvidenceOptions::check() const {
  using namespace option_check;
  at_least("MotionEvidenceOptions.static_factor", static_factor, 1);
  at_least("MotionEvidenceOptions.static_floor_px", static_floor_px, 0);
  if (moving_factor < static_factor) {
    throw OptionError("MotionEvidenceOptions.moving_factor", text(moving_factor),
                      "must be >= static_factor (" + text(static_factor) + ")");
  }
  if (moving_floor_px < static_floor_px) {
    throw OptionError("MotionEvidenceOptions.moving_floor_px", text(moving_floor_px),
                      "must be >= static_floor_px (" + text(static_floor_px) + ")");
  }
  if (object_moving_factor < static_factor) {
    throw OptionError("MotionEvidenceOptions.object_moving_factor", text(object_moving_factor),
                      "must be >= static_factor (" + text(static_factor) + ")");
  }
  if (object_moving_floor_px < static_floor_px) {
    throw OptionError("MotionEvidenceOptions.object_moving_floor_px", text(object_moving_floor_px),
                      "must be >= static_floor_px (" + text(static_floor_px) + ")");
  }
  at_least("MotionEvidenceOptions.min_matches", min_matches, 1);
  at_least("MotionEvidenceOptions.kept_min_matches", kept_min_matches, 1);
  if (kept_max_px < moving_floor_px) {
    throw OptionError("MotionEvidenceOptions.kept_max_px", text(kept_max_px),
                      "must be >= moving_floor_px (" + text(moving_floor_px) + ")");
  }
  at_least("MotionEvidenceOptions.min_background", min_background, 1);
  at_least("MotionEvidenceOptions.moving_weight", moving_weight, 1);
  at_least("MotionEvidenceOptions.default_frames", default_frames, 1);
  for (const auto& [category, frames] : frames_by_class) {
    at_least("MotionEvidenceOptions.frames_by_class[" + category + "]", frames, 1);
  }
}

int MotionEvidenceOptions::frames_for(const std::string& category) const {
  const auto it = frames_by_class.find(category);
  return it != frames_by_class.end() ? it->second : default_frames;
}

double median_of(std::vector<double>& values) {
  if (values.empty()) return 0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

MotionEvidence::MotionEvidence(MotionEvidenceOptions options) : options_(std::move(options)) { options_.check(); }

std::vector<InstanceMotionState> MotionEvidence::update(const std::vector<double>& background,
                                                        const std::vector<InstanceResiduals>& instances) {
  std::vector<double> bg = background;
  background_median_ = median_of(bg);
  const bool have_background = static_cast<int>(background.size()) >= options_.min_background;
  const double agree_px = std::max(options_.static_factor * background_median_, options_.static_floor_px);
  const double move_px = std::max(options_.moving_factor * background_median_, options_.moving_floor_px);
  const double object_move_px =
      std::max(options_.object_moving_factor * background_median_, options_.object_moving_floor_px);
  std::vector<InstanceMotionState> out;
  out.reserve(instances.size());
  for (const InstanceResiduals& instance : instances) {
    InstanceMotionState& s = states_[instance.id];
    s.id = instance.id;
    s.matches = static_cast<int>(instance.residuals.size());
    std::vector<double> r = instance.residuals;
    s.median_px = median_of(r);
    s.verdict = MotionVerdict::NoEvidence;
    if (have_background && s.matches >= options_.min_matches) {
      if (s.median_px <= agree_px) s.verdict = MotionVerdict::Agrees;
      if (s.median_px > (instance.object ? object_move_px : move_px)) s.verdict = MotionVerdict::Disagrees;
    }
    // A kept person (static as of the last frame) is not undone by a few or wild matches.
    if (s.verdict == MotionVerdict::Disagrees && !instance.object && s.is_static &&
        (s.matches < options_.kept_min_matches || s.median_px > options_.kept_max_px)) {
      s.verdict = MotionVerdict::NoEvidence;
    }
    const double needed = options_.frames_for(instance.category);
    if (s.verdict == MotionVerdict::Agrees) s.log_odds = std::min(s.log_odds + 1.0, needed);
    if (s.verdict == MotionVerdict::Disagrees) s.log_odds = std::max(0.0, s.log_odds - options_.moving_weight);
    // Static only while the evidence is full: one disagreeing frame ends it.
    s.is_static = s.log_odds >= needed;
    out.push_back(s);
  }
  return out;
}

std::vector<InstanceMotionState> MotionEvidence::peek(const std::vector<double>& background,
                                                      const std::vector<InstanceResiduals>& instances) const {
  MotionEvidence copy = *this;
  return copy.update(background, instances);
}

bool MotionEvidence::is_static(int id) const {
  const auto it = states_.find(id);
  return it != states_.end() && it->second.is_static;
}

}  // namespace stillslam
