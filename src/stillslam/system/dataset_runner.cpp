#include "stillslam/system/dataset_runner.h"

#include <chrono>
#include <future>
#include <thread>

#include "stillslam/core/error.h"
#include "stillslam/core/scope_exit.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/io/preloaded_dataset.h"
#include "stillslam/system/process_cpu_time.h"

namespace stillslam {

std::string to_string(RunEnd end) {
  switch (end) {
    case RunEnd::Finished: return "finished";
    case RunEnd::MaxFrames: return "max_frames";
    case RunEnd::Interrupted: return "interrupted";
    case RunEnd::InputError: return "input_error";
  }
  return "finished";
}

void collect_system_results(const System& system, RunResult& out) {
  for (const MapPose& p : system.trajectory_with_maps()) {
    out.trajectory.push_back(p.pose);
    out.trajectory_map_ids.push_back(p.map_id);
  }
  out.keyframes = system.keyframe_trajectory();
  out.mapper = system.mapper_stats();
  out.loop_closer = system.loop_closer_stats();
  for (const FrameStats& f : out.frames) out.relocalizations += f.reason == "relocalized" ? 1 : 0;
  out.map_points = system.num_map_points();
  out.maps = system.num_maps();
  out.new_maps = system.new_maps_started();
  out.merges = system.merges();
}

RunResult run_dataset(const Settings& settings, const Dataset& source, const RunOptions& options) {
  RunResult out;
  Stopwatch wall;
  const std::size_t first = std::min(options.first_frame, source.size());
  std::size_t n = source.size();
  if (options.max_frames) n = std::min(n, first + *options.max_frames);
  std::optional<PreloadedDataset> preloaded;
  if (options.preload_max_bytes) {
    Stopwatch decode;
    preloaded.emplace(source, first, n, *options.preload_max_bytes);
    out.preload_seconds = decode.elapsed_ms() / 1000.0;
    out.preloaded_frames = preloaded->frames();
    out.preloaded_bytes = preloaded->bytes();
  }
  const Dataset& dataset = preloaded ? static_cast<const Dataset&>(*preloaded) : source;
  System system(settings, dataset.sensor(), dataset.rectified_stereo(), options.system);

  std::optional<ProgressReporter> progress;
  if (options.progress) {
    ProgressOptions p = *options.progress;
    p.total_frames = n - std::min(first, n);
    progress.emplace(system.publisher(), p);
  }
  if (options.on_start) options.on_start(system);
  const ScopeExit end_notice(options.on_end);  // before `system` is destroyed, however this function leaves

  auto load = [&dataset](std::size_t i) { return dataset.load(i); };
  std::future<SensorFrame> next;
  std::size_t next_index = first;  // the frame `next` loads
  if (n > first) next = std::async(std::launch::async, load, first);
  const double t0 = n > first ? dataset.timestamp(first) : 0.0;
  double paused_seconds = 0;
  const double loop_start = wall.elapsed_ms() / 1000.0;
  const double cpu_start = process_cpu_seconds();
  double loop_end = loop_start;
  try {
    for (std::size_t i = first; i < n; ++i) {
      if (options.stop != nullptr && options.stop->load()) {
        out.interrupted = true;
        break;
      }
      if (options.pause != nullptr) {
        Stopwatch held;
        if (!options.pause->wait(options.stop)) {
          out.interrupted = true;
          break;
        }
        paused_seconds += held.elapsed_ms() / 1000.0;  // not late: realtime pacing starts again
      }
      if (options.realtime) {
        // A live camera: the newest frame that has arrived is taken, the ones
        // before it that the system was too busy for are dropped (and never loaded).
        const double now = wall.elapsed_ms() / 1000.0 - paused_seconds - loop_start;
        std::size_t newest = i;
        while (newest + 1 < n && dataset.timestamp(newest + 1) - t0 <= now) ++newest;
        out.dropped_frames += newest - i;
        i = newest;
      }
      if (next_index != i) {
        try {
          next.wait();
        } catch (...) {
        }
        next = std::async(std::launch::async, load, i);
      }
      SensorFrame frame = next.get();
      if (i + 1 < n) next = std::async(std::launch::async, load, i + 1);
      next_index = i + 1;
      // When the frame arrived, on the wall clock minus pauses.
      double arrival = wall.elapsed_ms() / 1000.0 - paused_seconds;
      if (options.realtime) {
        const double due = dataset.timestamp(i) - t0 + loop_start;
        if (due > arrival) std::this_thread::sleep_for(std::chrono::duration<double>(due - arrival));
        arrival = due;
      }
      if (!frame.valid) continue;
      FrameStats stats = system.process(frame);
      loop_end = wall.elapsed_ms() / 1000.0 - paused_seconds;
      stats.latency_ms = 1000.0 * (loop_end - arrival);
      mark_start_frames_posed(out.frames, stats);  // the frames the map's start waited on have poses now
      if (options.on_frame) options.on_frame(stats, system);
      out.frames.push_back(std::move(stats));
    }
  } catch (const Error& e) {
    out.error = e.what();
  }
  out.processing_seconds = loop_end - loop_start;
  out.process_cpu_seconds = process_cpu_seconds() - cpu_start;
  if (next.valid()) {
    try {
      next.wait();
    } catch (...) {
    }
  }
  if (progress) progress->stop();
  system.shutdown();
  if (!options.save_map.empty()) {
    try {
      Stopwatch save;
      out.map_file = system.save_map(options.save_map);
      out.save_map_ms = save.elapsed_ms();
    } catch (const Error& e) {
      out.map_file_error = e.what();
    }
  }
  collect_system_results(system, out);
  out.skipped_frames = source.skipped_frames();
  out.frames_in_input = dataset.size();
  if (out.error) {
    out.end = RunEnd::InputError;
  } else if (out.interrupted) {
    out.end = RunEnd::Interrupted;
  } else if (n < dataset.size()) {
    out.end = RunEnd::MaxFrames;
  }
  out.wall_seconds = wall.elapsed_ms() / 1000.0;
  return out;
}

}  // namespace stillslam
