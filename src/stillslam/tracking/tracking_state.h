#pragma once
namespace stillslam {

enum class TrackingState { NotInitialized, Ok, Lost };

inline const char* to_string(TrackingState s) {
  switch (s) {
    case TrackingState::NotInitialized: return "not_initialized";
    case TrackingState::Ok: return "ok";
    case TrackingState::Lost: return "lost";
  }
  return "unknown";
}

}  // namespace stillslam
