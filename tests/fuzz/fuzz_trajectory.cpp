// Trajectory files (io/trajectory): format detection and the TUM, KITTI and
// EuRoC readers on the same bytes; KITTI also with the file as its own times.
#include "fuzz/fuzz_support.h"
#include "stillslam/io/trajectory.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  const auto path = fuzz::input_file(data, size, "trajectory.txt");
  fuzz::expect_error_or_result([&] { read_trajectory(path); });
  for (TrajectoryFormat format : {TrajectoryFormat::Tum, TrajectoryFormat::Kitti, TrajectoryFormat::Euroc}) {
    fuzz::expect_error_or_result([&] { read_trajectory(path, format); });
  }
  fuzz::expect_error_or_result([&] { read_kitti_trajectory(path, path); });
  return 0;
}
