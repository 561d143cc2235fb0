#include "stillslam/settings/viewer_options.h"

#include "stillslam/core/option_check.h"
#include "stillslam/core/text.h"

namespace stillslam {

void ViewerOptions::check() const {
  option_check::in_range("ViewerOptions.port", port, 0, 65535);
  if (trim(host).empty()) throw OptionError("ViewerOptions.host", "empty", "must be a host name or address");
  option_check::in_range("ViewerOptions.image_rate", image_rate, 0.1, 60);
  option_check::in_range("ViewerOptions.map_rate", map_rate, 0.1, 30);
  option_check::in_range("ViewerOptions.jpeg_quality", jpeg_quality, 10, 100);
}

}  // namespace stillslam
