#include "stillslam/settings/settings.h"

#include "stillslam/core/shipped_files.h"
#include "stillslam/io/yaml_reader.h"
#include "stillslam/settings/section_binders.h"

namespace stillslam {

Settings load_settings(const std::filesystem::path& yaml) { return load_settings(yaml, running_executable()); }

Settings load_settings(const std::filesystem::path& yaml_file, const std::filesystem::path& executable) {
  const YamlReader yaml(yaml_file);
  Settings s;
  static_cast<CameraSettings&>(s) = read_camera_settings(yaml);
  bind_orb(yaml, s.orb);
  bind_stereo_matching(yaml, s.stereo_flow_matching);
  bind_segmentation(yaml, s.segmentation, executable);
  bind_tracking(yaml, s.fps, s.tracking, s.relocalization);
  bind_local_mapping(yaml, s.local_mapping);
  bind_loop_closing(yaml, s);
  bind_viewer(yaml, s.viewer);
  bind_mask_propagation(yaml, s.mask_propagation);
  bind_motion(yaml, s.motion);
  return s;
}

}  // namespace stillslam
