#include "io/dataset_fixtures.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace stillslam::test {
namespace fs = std::filesystem;

cv::Mat textured_image(int width, int height, int channels, int seed) {
  cv::RNG rng(static_cast<std::uint64_t>(seed) + 1);
  cv::Mat small(height / 4 + 1, width / 4 + 1, CV_8UC(channels));
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  cv::Mat image;
  cv::resize(small, image, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
  return image;
}

void truncate_copy(const fs::path& source, const fs::path& target, double fraction) {
  std::ifstream in(source, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream out(target, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(static_cast<double>(bytes.size()) * fraction));
}

fs::path write_tum_fixture(const fs::path& root, int frames) {
  const fs::path dir = root / "rgbd_dataset_freiburg3_test";
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  std::ofstream rgb(dir / "rgb.txt"), depth(dir / "depth.txt");
  rgb << "# color images\n# file: 'test'\n# timestamp filename\n";
  depth << "# depth maps\n# file: 'test'\n# timestamp filename\n";
  char stamp[64];
  for (int k = 0; k <= frames; ++k) {
    const double t = 100.0 + k / 30.0;
    std::snprintf(stamp, sizeof(stamp), "%.6f", t);
    cv::Mat color = textured_image(64, 48, 3, k);
    color.at<cv::Vec3b>(0, 0) = cv::Vec3b(10, 20, 30);  // B, G, R
    cv::imwrite((dir / "rgb" / (std::string(stamp) + ".png")).string(), color);
    rgb << stamp << " rgb/" << stamp << ".png\n";
    if (k == frames) break;  // the last rgb frame has no depth partner
    std::snprintf(stamp, sizeof(stamp), "%.6f", t + 0.004);
    cv::Mat d(48, 64, CV_16UC1, cv::Scalar(5000 + 100 * k));
    d.at<std::uint16_t>(0, 0) = 0;
    cv::imwrite((dir / "depth" / (std::string(stamp) + ".png")).string(), d);
    depth << stamp << " depth/" << stamp << ".png\n";
  }
  return dir;
}

fs::path write_kitti_fixture(const fs::path& root, int frames, bool with_calib) {
  const fs::path dir = root / "sequences" / "00";
  fs::create_directories(dir / "image_0");
  fs::create_directories(dir / "image_1");
  std::ofstream times(dir / "times.txt");
  char name[32];
  for (int k = 0; k < frames; ++k) {
    times << std::scientific << 0.1036 * k << "\n";
    std::snprintf(name, sizeof(name), "%06d.png", k);
    cv::imwrite((dir / "image_0" / name).string(), textured_image(96, 32, 1, 2 * k));
    cv::imwrite((dir / "image_1" / name).string(), textured_image(96, 32, 1, 2 * k + 1));
  }
  if (with_calib) {
    std::ofstream calib(dir / "calib.txt");
    calib << "P0: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 "
             "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
             "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00\n"
             "P1: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.861448000000e+02 "
             "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
             "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00\n"
             "P2: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 4.538225000000e+01 "
             "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 -1.130887000000e-01 "
             "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 3.779761000000e-03\n";
  }
  return dir;
}

namespace {

const char* kCam0Yaml = R"(%YAML:1.0
sensor_type: camera
comment: VI-Sensor cam0 (MT9M034)
T_BS:
  cols: 4
  rows: 4
  data: [0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,
         0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,
        -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,
         0.0, 0.0, 0.0, 1.0]
rate_hz: 20
resolution: [752, 480]
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
)";

const char* kCam1Yaml = R"(%YAML:1.0
sensor_type: camera
comment: VI-Sensor cam1 (MT9M034)
T_BS:
  cols: 4
  rows: 4
  data: [0.0125552670891, -0.999755099723, 0.0182237714554, -0.0198435579556,
         0.999598781151, 0.0130119051815, 0.0251588363115, 0.0453689425024,
        -0.0253898008918, 0.0179005838253, 0.999517347078, 0.00786212447038,
         0.0, 0.0, 0.0, 1.0]
rate_hz: 20
resolution: [752, 480]
camera_model: pinhole
intrinsics: [457.587, 456.134, 379.999, 255.238] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28368365,  0.07451284, -0.00010473, -3.55590700e-05]
)";

}  // namespace

fs::path write_euroc_fixture(const fs::path& root, int frames) {
  const fs::path seq = root / "V1_01_test";
  const fs::path mav0 = seq / "mav0";
  for (const char* cam : {"cam0", "cam1"}) fs::create_directories(mav0 / cam / "data");
  fs::create_directories(mav0 / "imu0");
  std::ofstream(mav0 / "cam0" / "sensor.yaml") << kCam0Yaml;
  std::ofstream(mav0 / "cam1" / "sensor.yaml") << kCam1Yaml;
  std::ofstream c0(mav0 / "cam0" / "data.csv"), c1(mav0 / "cam1" / "data.csv");
  c0 << "#timestamp [ns],filename\r\n";  // CRLF: some EuRoC copies were written on Windows
  c1 << "#timestamp [ns],filename\r\n";
  const long long t0 = 1403715273262142976LL;
  for (int k = 0; k < frames; ++k) {
    const std::string ts = std::to_string(t0 + 50000000LL * k);
    c0 << ts << "," << ts << ".png\r\n";
    c1 << ts << "," << ts << ".png\r\n";
    cv::imwrite((mav0 / "cam0" / "data" / (ts + ".png")).string(), textured_image(752, 480, 1, 3 * k));
    cv::imwrite((mav0 / "cam1" / "data" / (ts + ".png")).string(), textured_image(752, 480, 1, 3 * k + 1));
  }
  std::ofstream imu(mav0 / "imu0" / "data.csv");
  imu << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
         "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  for (int k = 0; k < 10 * frames; ++k) {
    imu << t0 + 5000000LL * k << "," << 0.01 * k << ",0.02,-0.03,9.81,0.1," << -0.1 * k << "\n";
  }
  return seq;
}

}  // namespace stillslam::test
