#pragma once
// Internal to settings/: one binder per settings section, each in its own
// file (<section>_settings.cpp). Each reads its keys into the Options
// defaults it is given, runs their check() and reports errors under the key.
#include <filesystem>

#include "stillslam/io/yaml_reader.h"
#include "stillslam/settings/settings.h"

namespace stillslam {

void bind_orb(const YamlReader& yaml, OrbOptions& orb);                        // ORBextractor.*
void bind_stereo_matching(const YamlReader& yaml, bool& flow_matching);        // Stereo.flowMatching
// Segmentation.*; without Segmentation.model the shipped model is looked for
// from `executable` (next to it and in its parent folders).
void bind_segmentation(const YamlReader& yaml, SegmentationOptions& options,
                       const std::filesystem::path& executable);
// Tracking.*; `fps` (Camera.fps) is the default of maxFramesBetweenKeyframes.
void bind_tracking(const YamlReader& yaml, double fps, TrackerOptions& tracker, RelocalizerOptions& relocalizer);
void bind_local_mapping(const YamlReader& yaml, LocalMapperOptions& options);  // LocalMapping.*
void bind_loop_closing(const YamlReader& yaml, Settings& settings);             // LoopClosing.*
void bind_viewer(const YamlReader& yaml, ViewerOptions& options);              // Viewer.port, Viewer.host
void bind_mask_propagation(const YamlReader& yaml, MaskPropagationOptions& options);  // MaskPropagation.*
void bind_motion(const YamlReader& yaml, MotionOptions& options);  // Motion.*

}  // namespace stillslam
