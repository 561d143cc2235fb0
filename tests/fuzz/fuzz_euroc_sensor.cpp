// EuRoC sensor.yaml (io/euroc_dataset read_euroc_camera, through io/yaml_reader).
#include "fuzz/fuzz_support.h"
#include "stillslam/io/euroc_dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  const auto path = fuzz::input_file(data, size, "sensor.yaml");
  fuzz::expect_error_or_result([&] { read_euroc_camera(path); });
  return 0;
}
