#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <string>

#include "stillslam/settings/section_binders.h"
#include "stillslam/settings/section_keys.h"

namespace stillslam {
namespace {

// ORB-SLAM3's Viewer.* keys (its Pangolin window): users' files carry them.
constexpr std::array<const char*, 11> kOrbSlamViewerKeys = {
    "KeyFrameSize", "KeyFrameLineWidth", "GraphLineWidth", "PointSize",  "CameraSize",    "CameraLineWidth",
    "ViewpointX",   "ViewpointY",        "ViewpointZ",     "ViewpointF", "imageViewScale"};

}  // namespace

// Viewer.* is shared with ORB-SLAM3, so other keys only warn: a misspelt
// stillslam key is named, ORB-SLAM3's are accepted silently.
void bind_viewer(const YamlReader& yaml, ViewerOptions& options) {
  SectionKeys keys(yaml, "Viewer", false);
  keys.integer("port", options.port, "ViewerOptions.port", {0, 65535});
  keys.number("image_rate", options.image_rate, "ViewerOptions.image_rate", {0.1, 60});
  keys.number("map_rate", options.map_rate, "ViewerOptions.map_rate", {0.1, 30});
  keys.integer("jpeg_quality", options.jpeg_quality, "ViewerOptions.jpeg_quality", {10, 100});
  const cv::FileNode host = keys.node("host");
  if (!host.isNone()) {
    if (!host.isString()) keys.fail("host", "must be a string (a host name or address, e.g. \"127.0.0.1\")");
    options.host = static_cast<std::string>(host);
  }
  keys.check([&] { options.check(); });
  for (const std::string& key : yaml.keys()) {
    if (key.rfind("Viewer.", 0) != 0) continue;
    const std::string name = key.substr(7);
    const bool orb_slam = std::any_of(kOrbSlamViewerKeys.begin(), kOrbSlamViewerKeys.end(),
                                      [&](const char* k) { return name == k; });
    const bool ours = name == "port" || name == "host" || name == "image_rate" || name == "map_rate" ||
                      name == "jpeg_quality";
    if (!orb_slam && !ours) {
      spdlog::warn("{}: key '{}' is neither a stillslam Viewer setting (Viewer.port, Viewer.host, "
                   "Viewer.image_rate, Viewer.map_rate, Viewer.jpeg_quality) nor one of "
                   "ORB-SLAM3's; ignored", yaml.file().string(), key);
    }
  }
}

}  // namespace stillslam
