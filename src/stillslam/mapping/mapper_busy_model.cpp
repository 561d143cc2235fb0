#include "stillslam/mapping/mapper_busy_model.h"

#include <algorithm>

#include "stillslam/core/option_check.h"

namespace stillslam {

void MapperBusyModelOptions::check() const {
  option_check::in_range("MapperBusyModelOptions.keyframe_ms", keyframe_ms, 0.0, 10000.0);
  option_check::in_range("MapperBusyModelOptions.observation_us", observation_us, 0.0, 1000.0);
  option_check::in_range("MapperBusyModelOptions.observation_iteration_us", observation_iteration_us, 0.0, 1000.0);
}

MapperBusyModel::MapperBusyModel(MapperBusyModelOptions options) : options_(options) { options_.check(); }

double MapperBusyModel::busy_ms(int observations, int iterations) const {
  return options_.keyframe_ms +
         observations * (options_.observation_us + iterations * options_.observation_iteration_us) / 1000.0;
}

void MapperBusyModel::add(double arrival, double busy_ms) {
  const double start = std::max(arrival, busy_until_);
  busy_until_ = start + busy_ms / 1000.0;
  starts_.push_back(start);
  // Keyframes that started before this one arrived are no longer waiting at
  // any later `now` (callers ask about times from `arrival` on).
  while (starts_.size() > 1 && starts_.front() <= arrival) starts_.pop_front();
}

bool MapperBusyModel::idle(double now) const { return now >= busy_until_; }

std::size_t MapperBusyModel::queued(double now) const {
  return static_cast<std::size_t>(
      std::count_if(starts_.begin(), starts_.end(), [now](double start) { return start > now; }));
}

void MapperBusyModel::reset() {
  starts_.clear();
  busy_until_ = 0;
}

}  // namespace stillslam
