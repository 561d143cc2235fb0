#include "stillslam/place/binary_descriptor.h"

#include <string>

#include "stillslam/core/error.h"

namespace stillslam::place_detail {

std::vector<Descriptor256> pack_rows(const cv::Mat& descriptors, const char* what) {
  std::vector<Descriptor256> out;
  if (descriptors.empty()) return out;
  if (descriptors.type() != CV_8UC1 || descriptors.cols != 32)
    throw Error(std::string(what) + ": expected N x 32 CV_8U ORB descriptors, got " +
                std::to_string(descriptors.rows) + " x " + std::to_string(descriptors.cols) + " of type " +
                std::to_string(descriptors.type()));
  out.reserve(static_cast<std::size_t>(descriptors.rows));
  for (int r = 0; r < descriptors.rows; ++r) out.push_back(pack(descriptors.ptr<std::uint8_t>(r)));
  return out;
}

}  // namespace stillslam::place_detail
