// MCAP bags (io/mcap_reader): the record scan, chunk decompression (zstd,
// lz4, none), the summary, then every message read and decoded as its
// topic's type says (io/ros2_message_codec).
#include "fuzz/fuzz_support.h"
#include "stillslam/io/mcap_reader.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/io/ros2_message_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  const auto path = fuzz::input_file(data, size, "bag.mcap");
  fuzz::expect_error_or_result([&] {
    const McapReader bag(path);
    for (std::size_t i = 0; i < bag.messages().size() && i < 64; ++i) {
      const std::string& type = bag.topics()[bag.messages()[i].topic].type;
      fuzz::expect_error_or_result([&] {
        const auto bytes = bag.read(i);
        (void)bag.read_prefix(i, 12);
        if (type == ros2::kImageType) (void)ros2::image_to_mat(ros2::decode_image(bytes, "fuzz"), "fuzz");
        if (type == ros2::kOdometryType) (void)ros2::decode_odometry(bytes, "fuzz");
        if (type == ros2::kTfMessageType) (void)ros2::decode_tf_message(bytes, "fuzz");
        if (type == ros2::kCameraInfoType) (void)ros2::decode_camera_info(bytes, "fuzz");
      });
    }
  });
  return 0;
}
