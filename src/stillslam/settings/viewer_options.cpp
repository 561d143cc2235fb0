#include "stillslam/settings/viewer_options.h"

#include "stillslam/core/option_check.h"
#include "stillslam/core/text.h"

namespace stillslam {

void ViewerOptions::check() const {
  option_check::in_range("ViewerOptions.port", port, 1, 65535);
  if (trim(host).empty()) throw OptionError("ViewerOptions.host", "empty", "must be a host name or address");
}

}  // namespace stillslam
