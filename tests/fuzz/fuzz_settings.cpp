// Settings YAML: load_settings (every section, through io/yaml_reader and
// io/camera_settings) and load_camera_settings on the same file.
#include "fuzz/fuzz_support.h"
#include "stillslam/io/camera_settings.h"
#include "stillslam/settings/settings.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  const auto path = fuzz::input_file(data, size, "settings.yaml");
  // The shipped segmentation model is looked for from here: not found, so
  // only a Segmentation.model key names one.
  const auto executable = fuzz::temp_folder() / "bin" / "stillslam";
  fuzz::expect_error_or_result([&] { load_settings(path, executable); });
  fuzz::expect_error_or_result([&] { load_camera_settings(path); });
  return 0;
}
