#pragma once
// Base64 (RFC 4648, with padding) for the JPEG frames in the event stream:
// the page shows them as data: URLs, each with the overlay of its own frame.
#include <cstdint>
#include <string>
#include <vector>

namespace stillslam::viewer {

std::string base64(const std::vector<std::uint8_t>& bytes);

}  // namespace stillslam::viewer
