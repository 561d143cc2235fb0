#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {

// Stereo.flowMatching; the other Stereo.* keys (b, ThDepth, T_c1_c2) are
// the camera's (io/camera_settings.h).
void bind_stereo_matching(const YamlReader& yaml, bool& flow_matching) {
  SectionKeys keys(yaml, "Stereo", false);
  const cv::FileNode n = keys.node("flowMatching");
  if (n.isNone()) return;
  const auto v = node_number(n);
  if (!v || (*v != 0 && *v != 1)) {
    keys.fail("flowMatching", "must be 0 (descriptor matches only) or 1 (optical flow for the rest)");
  }
  flow_matching = *v == 1;
}

}  // namespace stillslam
