// Simulator timings: one 640x480 frame (colour, depth, mask) per noise level,
// with stereo, and writing a short sequence to disk. Plain main (prints a
// table) so it runs with or without Google Benchmark. CPU time is reported
// next to wall time because the machine may be shared.
//
//   build/bench/bench_simulate [--frames N]
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>

#include "stillslam/core/stopwatch.h"
#include "stillslam/sim/sequence_writer.h"
#include "stillslam/sim/simulator.h"

namespace {

struct Timing {
  double wall_ms = 0, cpu_ms = 0;
};

template <typename F>
Timing time_it(int repeats, F&& f) {
  stillslam::Stopwatch sw;
  const std::clock_t c0 = std::clock();
  for (int i = 0; i < repeats; ++i) f(i);
  return {sw.elapsed_ms() / repeats, 1000.0 * (std::clock() - c0) / CLOCKS_PER_SEC / repeats};
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 20;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--frames") == 0) frames = std::stoi(argv[i + 1]);
  }
  std::printf("%-44s %10s %10s\n", "case (640x480, walking_xyz, 2 people)", "wall ms", "cpu ms");
  auto row = [&](const char* name, stillslam::sim::SimulationOptions o) {
    o.frames = frames;
    const stillslam::sim::Simulator sim(o);
    const Timing t = time_it(sim.frame_count(), [&](int i) { sim.render_frame(i); });
    std::printf("%-44s %10.1f %10.1f\n", name, t.wall_ms, t.cpu_ms);
  };
  stillslam::sim::SimulationOptions base;
  row("render frame, noise 0", base);
  auto o = base;
  o.noise = 1;
  row("render frame, noise 1 (3-pose motion blur)", o);
  o.noise = 2;
  row("render frame, noise 2 (5-pose motion blur)", o);
  o = base;
  o.stereo = true;
  row("render frame + right image, noise 0", o);
  o = base;
  o.supersampling = 1;
  row("render frame, no anti-aliasing", o);

  const auto dir = std::filesystem::temp_directory_path() / "stillslam_bench_simulate";
  std::filesystem::remove_all(dir);
  o = base;
  o.frames = frames;
  stillslam::Stopwatch sw;
  const std::clock_t c0 = std::clock();
  const auto s = stillslam::sim::write_sequence(dir, o);
  std::printf("%-44s %10.1f %10.1f\n", "write_sequence per frame (render + 3 PNGs)", sw.elapsed_ms() / s.frames,
              1000.0 * (std::clock() - c0) / CLOCKS_PER_SEC / s.frames);
  std::filesystem::remove_all(dir);
  return 0;
}
