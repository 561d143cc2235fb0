#pragma once
// Map save and load: a binary, versioned file holding one or more maps (an
// atlas) with everything tracking needs to localize against them again.
//
// Saved per keyframe: id, frame id, timestamp, pose, undistorted keypoints,
// descriptors, right coordinates and depths, map-point slots and the
// spanning-tree parent; per map point: id, position, descriptor, normal,
// distance range, reference keyframe, observations and found/visible counts;
// per map: id, loop edges; the atlas' next-id counters. Only active (not culled)
// keyframes and good points are saved. Covisibility (and, by the caller,
// bag-of-words) is rebuilt on load rather than stored.
//
// The file also records what the map was made with (sensor, camera model,
// calibration, pyramid, a fingerprint of the vocabulary); load refuses a map
// that does not fit the running system with a stillslam::Error naming the
// file, as it does for a file that is not a map, has another format version,
// or is truncated or corrupt (FNV-1a checksum over the whole file).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "stillslam/map/camera_setup.h"
#include "stillslam/map/map.h"

namespace stillslam {

class Vocabulary;

inline constexpr std::uint32_t kMapFileVersion = 1;

// Keyframe id pairs (both directions) of closed loops, as LoopCloser keeps them.
using MapLoopEdges = std::set<std::pair<std::uint64_t, std::uint64_t>>;

// What the maps were made with. Saved in the file; on load it must match.
struct MapFileContext {
  std::string sensor;                         // e.g. "rgbd", "stereo"
  std::shared_ptr<const CameraSetup> setup;   // keyframes of loaded maps share it
  std::uint64_t vocabulary_checksum = 0;      // vocabulary_fingerprint(); 0: no vocabulary
};

// A content fingerprint of a vocabulary (tree shape, word nodes and weights,
// the words of a fixed set of probe descriptors): equal for the same
// vocabulary however it was loaded, different for another one.
std::uint64_t vocabulary_fingerprint(const Vocabulary& vocabulary);

struct MapToSave {
  const Map* map = nullptr;  // saved with its id
  MapLoopEdges loop_edges;
};

struct LoadedMap {
  std::uint64_t id = 0;
  std::unique_ptr<Map> map;
  MapLoopEdges loop_edges;
};

struct MapFileContents {
  std::vector<LoadedMap> maps;
  std::uint64_t active_map_id = 0;
  // Atlas-wide counters at save time (>= every id in the file).
  std::uint64_t next_map_id = 0, next_keyframe_id = 0, next_point_id = 0;
};

struct MapFileSaveOptions {
  // zstd: files about a third smaller (descriptors barely compress, the
  // rest does) for ~10 ms per MB to save and a few ms per MB to load.
  bool compress = true;
  int zstd_level = 3;
};

struct MapFileStats {
  std::uint64_t bytes = 0;      // file size
  std::uint64_t raw_bytes = 0;  // payload before compression
  std::size_t maps = 0, keyframes = 0, map_points = 0;  // map_points: those saved
  std::size_t points_on_people = 0;  // left out: MapPoint::on_dynamic_instance()
};

// Writes the maps (callers hold each map's update mutex, or no other thread
// runs). Written to a temporary file next to it and renamed
// (core/atomic_file.h), so an existing file is replaced only by a complete one
// and no temporary file is left behind. Throws Error naming the file and the
// cause (e.g. "No space left on device", "Is a directory") when it can't be written.
MapFileStats save_map_file(const std::filesystem::path& path, const MapFileContext& context,
                           const std::vector<MapToSave>& maps, std::uint64_t active_map_id = 0,
                           std::uint64_t next_map_id = 0, const MapFileSaveOptions& options = {});
// Convenience: one map (active).
MapFileStats save_map_file(const std::filesystem::path& path, const MapFileContext& context, const Map& map,
                           const MapLoopEdges& loop_edges = {}, const MapFileSaveOptions& options = {});

// Reads the maps; their keyframes use `expected.setup`, they share `ids`
// (an Atlas' counters; new ones when null), which are raised past every id in
// the file. Throws Error (naming
// the file and the fix) when the file is missing, not a map file, of another
// version, truncated or corrupt, or made with another sensor, calibration or
// vocabulary than `expected`.
MapFileContents load_map_file(const std::filesystem::path& path, const MapFileContext& expected,
                              const std::shared_ptr<MapIdCounters>& ids = nullptr);

}  // namespace stillslam
