#include "stillslam/system/progress.h"

#include <cmath>

namespace stillslam {

namespace {

std::string duration_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buffer[32];
  if (s >= 3600) {
    std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  } else if (s >= 60) {
    std::snprintf(buffer, sizeof buffer, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%lds", s);
  }
  return buffer;
}

}  // namespace

std::string format_progress(const FrameSnapshot& frame, const AtlasSnapshot* atlas, std::size_t frames_done,
                            std::size_t total_frames, double elapsed_s) {
  char buffer[256];
  std::string out;
  if (total_frames > 0) {
    std::snprintf(buffer, sizeof buffer, "frame %zu/%zu (%.1f%%)", frames_done, total_frames,
                  100.0 * static_cast<double>(frames_done) / static_cast<double>(total_frames));
  } else {
    std::snprintf(buffer, sizeof buffer, "frame %zu", frames_done);
  }
  out += buffer;
  const double fps = elapsed_s > 0 ? static_cast<double>(frames_done) / elapsed_s : 0.0;
  std::snprintf(buffer, sizeof buffer, "  %.1f fps  %s", fps, frame.state.c_str());
  out += buffer;
  if (atlas) {
    for (const MapSnapshot& m : atlas->maps) {
      if (m.map_id != frame.map_id) continue;
      std::snprintf(buffer, sizeof buffer, "  map %llu: %zu kf, %zu pts", static_cast<unsigned long long>(m.map_id),
                    m.keyframes.size(), m.points.size());
      out += buffer;
    }
    if (atlas->maps.size() > 1) out += "  (" + std::to_string(atlas->maps.size()) + " maps)";
    if (atlas->loops_closed > 0) out += "  loops " + std::to_string(atlas->loops_closed);
  }
  if (total_frames > frames_done && fps > 0) {
    out += "  ETA " + duration_text(static_cast<double>(total_frames - frames_done) / fps);
  }
  return out;
}

ProgressReporter::ProgressReporter(const Publisher& publisher, ProgressOptions options, std::FILE* out)
    : publisher_(publisher),
      options_(options),
      out_(out),
      start_(std::chrono::steady_clock::now()),
      thread_([this] { run(); }) {}

ProgressReporter::~ProgressReporter() { stop(); }

void ProgressReporter::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return;
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  print(true);
}

void ProgressReporter::run() {
  const auto interval = options_.terminal ? options_.terminal_interval : options_.plain_interval;
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, interval, [&] { return stopping_; })) {
    lock.unlock();
    print(false);
    lock.lock();
  }
}

void ProgressReporter::print(bool final_line) {
  const Publisher::FrameRead frame = publisher_.frame();
  if (!frame.value) return;
  if (frame.version == printed_version_ && !(final_line && options_.terminal)) return;
  printed_version_ = frame.version;
  const Publisher::AtlasRead atlas = publisher_.atlas();
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string line = format_progress(*frame.value, atlas.value.get(), frame.value->frame_id + 1,
                                           options_.total_frames, elapsed);
  if (options_.terminal) {
    // \033[K clears what a longer earlier line left behind.
    std::fprintf(out_, "\r%s\033[K%s", line.c_str(), final_line ? "\n" : "");
  } else {
    std::fprintf(out_, "%s\n", line.c_str());
  }
  std::fflush(out_);
}

}  // namespace stillslam
