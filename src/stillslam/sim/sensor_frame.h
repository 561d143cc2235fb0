#pragma once
// A rendered frame as the SLAM system takes it from a dataset reader, for
// tests and benches that run the system on frames rendered in memory.
#include "stillslam/io/dataset.h"
#include "stillslam/sim/simulator.h"

namespace stillslam::sim {

// Colour, gray and, for RGB-D, depth; for stereo the right image instead.
// Named "sim<index>".
SensorFrame to_sensor_frame(const SimFrame& frame, SensorType sensor = SensorType::Rgbd);

}  // namespace stillslam::sim
