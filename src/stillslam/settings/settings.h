#pragma once
// Run settings: an ORB-SLAM3-compatible OpenCV YAML file bound to the Options
// of each module. The camera keys are io's (CameraSettings); every other
// section fills one Options struct: ORBextractor.* (features), Stereo.flowMatching,
// Segmentation.*, MaskPropagation.*, Tracking.*, LocalMapping.*, LoopClosing.*, Viewer.*.
// config/README.md lists every key with its default and range. A key left out
// keeps the Options default; a bad value is an Error naming the file and key.
#include <filesystem>

#include "stillslam/features/orb_options.h"
#include "stillslam/io/camera_settings.h"
#include "stillslam/loop/loop_closer_options.h"
#include "stillslam/loop/map_merger.h"
#include "stillslam/loop/place_recognizer.h"
#include "stillslam/mapping/local_mapper_options.h"
#include "stillslam/segmentation/mask_propagation.h"
#include "stillslam/segmentation/segmentation_options.h"
#include "stillslam/settings/viewer_options.h"
#include "stillslam/tracking/motion_options.h"
#include "stillslam/tracking/relocalizer.h"
#include "stillslam/tracking/tracker_options.h"

namespace stillslam {

struct Settings : CameraSettings {
  OrbOptions orb;                            // ORBextractor.*
  bool stereo_flow_matching = false;         // Stereo.flowMatching: optical flow for unmatched left keypoints
  // Segmentation.*; the model path is absolute (relative keys are read from
  // the file's directory; without the key, the shipped model).
  SegmentationOptions segmentation;
  // Tracking.*; max_frames_between_keyframes defaults to Camera.fps.
  TrackerOptions tracking;
  RelocalizerOptions relocalization;         // Tracking.reloc*
  LocalMapperOptions local_mapping;          // LocalMapping.*
  LoopCloserOptions loop_closing;            // LoopClosing.*
  PlaceRecognizerOptions place_recognition;  // LoopClosing.maxCandidates, minCommonWordsRatio
  bool map_merging = true;                   // LoopClosing.mapMerging
  MapMergerOptions map_merger;               // LoopClosing.merge*
  ViewerOptions viewer;                      // Viewer.port, Viewer.host
  MaskPropagationOptions mask_propagation;   // MaskPropagation.*
  MotionOptions motion;                      // Motion.*
};

// The most threads a thread-count key (Segmentation.threads, *.baThreads)
// may ask for: 64, or 4 per core on a machine with more than 16 cores.
// Far more than cores only slows a run; 100000 crashed TBB's teardown.
int max_threads();

// Reads and validates a settings file; throws stillslam::Error naming the file
// and the offending key. Without Segmentation.model the shipped model is
// looked for next to the running executable and in its parent folders.
Settings load_settings(const std::filesystem::path& yaml);
// The same, looking for the shipped model from `executable` instead.
Settings load_settings(const std::filesystem::path& yaml, const std::filesystem::path& executable);

}  // namespace stillslam
