#pragma once
// Internal to io/: the parts of load_settings() that live in their own files.
#include "stillslam/io/yaml_reader.h"
#include "stillslam/segmentation/segmentation_options.h"

namespace stillslam {

// Segmentation.* keys (flat, or nested under a "Segmentation:" map). Unknown
// keys are an error listing the known ones; the model path is made absolute
// relative to the settings file's directory.
void read_segmentation_section(const YamlReader& yaml, SegmentationOptions& options);

}  // namespace stillslam
