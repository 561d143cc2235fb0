#include "stillslam/place/binary_descriptor.h"

#include <string>

#include "stillslam/core/check.h"

namespace stillslam::place_detail {

std::vector<Descriptor256> pack_rows(const cv::Mat& descriptors, const char* what) {
  std::vector<Descriptor256> out;
  if (descriptors.empty()) return out;
  STILLSLAM_CHECK_EQ(descriptors.type(), CV_8UC1, std::string(what) + ": pass N x 32 CV_8U ORB descriptors");
  STILLSLAM_CHECK_EQ(descriptors.cols, 32, std::string(what) + ": pass N x 32 CV_8U ORB descriptors");
  out.reserve(static_cast<std::size_t>(descriptors.rows));
  for (int r = 0; r < descriptors.rows; ++r) out.push_back(pack(descriptors.ptr<std::uint8_t>(r)));
  return out;
}

}  // namespace stillslam::place_detail
