#include "stillslam/benchmark/html_text.h"

#include "stillslam/core/base64.h"

namespace stillslam {

std::string data_uri(const std::string& mime, const std::vector<std::uint8_t>& bytes) {
  return "data:" + mime + ";base64," + base64_encode(bytes);
}

std::string inline_svg(const std::string& svg) {
  const std::size_t start = svg.find("<svg");
  return start == std::string::npos ? svg : svg.substr(start);
}

}  // namespace stillslam
