// EuRoC lists: the input is cam0/data.csv, cam1/data.csv and imu0/data.csv of
// a sequence whose sensor.yaml files are valid (written once), read by the
// EurocDataset constructor (lists, pairing, IMU log, calibration).
#include "fuzz/fuzz_support.h"
#include "stillslam/io/euroc_dataset.h"

namespace {

constexpr const char* kSensorYaml = R"(%YAML:1.0
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375]
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
resolution: [752, 480]
T_BS:
  rows: 4
  cols: 4
  data: [1.0, 0.0, 0.0, %s, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]
)";

std::string sensor_yaml(const char* x) {
  std::string text = kSensorYaml;
  text.replace(text.find("%s"), 2, x);
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  const auto mav0 = fuzz::temp_folder() / "mav0";
  static const bool calibrated = [&] {
    fuzz::write_file(mav0 / "cam0" / "sensor.yaml", sensor_yaml("0.0"));
    fuzz::write_file(mav0 / "cam1" / "sensor.yaml", sensor_yaml("0.11"));
    return true;
  }();
  (void)calibrated;
  const std::string_view csv(reinterpret_cast<const char*>(data), size);
  for (const char* list : {"cam0", "cam1", "imu0"}) fuzz::write_file(mav0 / list / "data.csv", csv);
  fuzz::expect_error_or_result([&] { EurocDataset(mav0, CameraSettings{}, DatasetOptions{}); });
  return 0;
}
