// CDR payloads (io/cdr_reader, io/ros2_message_codec): the first byte picks
// the message type, the rest is its CDR; raw images also go through
// image_to_mat (every encoding, step and byte order checks). Compressed
// images are decoded by OpenCV and are not fuzzed here.
#include "fuzz/fuzz_support.h"
#include "stillslam/io/ros2_image_convert.h"
#include "stillslam/io/ros2_message_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stillslam;
  if (size < 1) return 0;
  const ros2::Bytes cdr(data + 1, data + size);
  fuzz::expect_error_or_result([&] {
    switch (data[0] % 7) {
      case 0: (void)ros2::image_to_mat(ros2::decode_image(cdr, "fuzz"), "fuzz"); break;
      case 1: (void)ros2::decode_compressed_image(cdr, "fuzz"); break;
      case 2: (void)ros2::decode_camera_info(cdr, "fuzz"); break;
      case 3: (void)ros2::decode_pose_stamped(cdr, "fuzz"); break;
      case 4: (void)ros2::decode_odometry(cdr, "fuzz"); break;
      case 5: (void)ros2::decode_tf_message(cdr, "fuzz"); break;
      default: (void)ros2::decode_stamp_ns(cdr, "fuzz"); break;
    }
  });
  return 0;
}
