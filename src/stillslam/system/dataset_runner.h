#pragma once
// Runs a whole dataset through a System: loads frames ahead on a helper
// thread, optionally paces them like a live camera, reports each frame to a
// callback (live trajectory, progress), stops on request, and always returns
// what it has (an input error ends the run but keeps the trajectory so far).
#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stillslam/io/dataset.h"
#include "stillslam/system/pause_gate.h"
#include "stillslam/system/progress.h"
#include "stillslam/system/system.h"

namespace stillslam {

// --preload's default bound (MB = 2^20 bytes): 800 RGB-D frames of 640x480 take 1.9 GB.
inline constexpr std::size_t kDefaultPreloadLimitMb = 4096;

struct RunOptions {
  SystemOptions system;
  std::optional<std::size_t> max_frames;
  std::size_t first_frame = 0;  // start this many frames into the dataset
  // Save every map here at the end (System::save_map), also when the run
  // stopped early (interrupted, input error).
  std::filesystem::path save_map;
  // Pace frames by their timestamps; frames whose time has passed while the
  // system was busy are dropped (not even loaded), as with a live camera
  // whose newest frame is taken.
  bool realtime = false;
  // Decode the frames to be run into memory before the clock starts (and
  // before the System is built), so decoding the dataset's files is not paid
  // inside the run, as with a camera that delivers pixels. The run refuses
  // (Error) when they would take more than this many bytes. Empty: each
  // frame is loaded on a helper thread while the run goes.
  std::optional<std::size_t> preload_max_bytes;
  // Checked before each frame (also before the first one: a stop requested
  // while the system was being built ends the run with no frame processed).
  const std::atomic<bool>* stop = nullptr;
  // Waited on before each frame (the viewer's pause / step / resume).
  PauseGate* pause = nullptr;
  // Called once the System exists (a viewer attaches to its publisher) and
  // before it is destroyed (the viewer lets go of it).
  std::function<void(const System&)> on_start;
  std::function<void()> on_end;
  std::function<void(const FrameStats&, const System&)> on_frame;
  // A progress line on stderr while the run lasts (total_frames is filled in).
  std::optional<ProgressOptions> progress;
};

// How a run ended, written as stats.json's "end" marker.
enum class RunEnd {
  Finished,     // every frame of the input went through
  MaxFrames,    // stopped after RunOptions::max_frames, the input has more
  Interrupted,  // RunOptions::stop was set
  InputError,   // a frame could not be read; `error` says why
};
std::string to_string(RunEnd end);

struct RunResult {
  RunEnd end = RunEnd::Finished;
  std::size_t frames_in_input = 0;  // the dataset's frame count
  std::vector<FrameStats> frames;
  Trajectory trajectory;  // final estimate, every tracked frame
  std::vector<std::uint64_t> trajectory_map_ids;  // per trajectory pose: the map it is expressed in
  Trajectory keyframes;
  LocalMapperStats mapper;
  LoopCloserStats loop_closer;  // zeros without a vocabulary
  int relocalizations = 0;      // frames recovered from Lost by relocalization
  std::size_t dropped_frames = 0;  // realtime mode
  std::size_t skipped_frames = 0;  // unreadable frames skipped by the dataset
  std::size_t preloaded_frames = 0;  // RunOptions::preload_max_bytes: frames held in memory
  std::size_t preloaded_bytes = 0;
  double preload_seconds = 0;  // decoding them, before the run's clock started
  bool interrupted = false;
  std::optional<std::string> error;  // the Error that ended the run early
  double wall_seconds = 0;
  // From the first frame taken to the end of the last one's process(), and
  // the CPU time of the whole process (every thread) meanwhile.
  double processing_seconds = 0;
  double process_cpu_seconds = 0;
  std::size_t map_points = 0;
  std::size_t maps = 1;           // at the end (after merges)
  int new_maps = 0;               // started because tracking stayed lost
  std::vector<MapMergeStats> merges;
  std::optional<MapFileStats> map_file;   // RunOptions::save_map written
  std::optional<std::string> map_file_error;  // or why not
  double save_map_ms = 0;
};

// Fills `out` from a system that has shut down: the trajectory with map
// ids, keyframes, mapping and loop-closing totals, relocalizations (from
// out.frames), map points, maps, new maps and merges. For other front ends
// than run_dataset (the live ROS 2 node).
void collect_system_results(const System& system, RunResult& out);

// Construction errors (bad settings for this sensor, model) throw; errors
// while reading frames end the run and are returned in `error`.
RunResult run_dataset(const Settings& settings, const Dataset& dataset, const RunOptions& options);

}  // namespace stillslam
