#include "frame_saver.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "stillslam/core/error.h"
#include "stillslam/core/option_check.h"
#include "stillslam/core/stopwatch.h"

namespace stillslam::apps {

void FrameSaverOptions::check() const {
  using namespace option_check;
  if (dir.empty()) throw Error("--save-frames needs a folder");
  at_least("--save-frames-every", every, 1);
  at_least("FrameSaverOptions.queue_frames", static_cast<double>(queue_frames), 1);
  if (format != "png" && format != "jpg") throw Error("--save-frames-format is " + format + ": use png or jpg");
  drawing.check();
}

namespace {

std::vector<std::filesystem::path> earlier_frames(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && name.rfind("frame_", 0) == 0 && (ext == ".png" || ext == ".jpg")) {
      files.push_back(e.path());
    }
  }
  return files;
}

}  // namespace

FrameSaver::FrameSaver(FrameSaverOptions options) : options_(std::move(options)), queue_(options_.queue_frames) {
  options_.check();
  std::error_code ec;
  std::filesystem::create_directories(options_.dir, ec);
  if (ec || !std::filesystem::is_directory(options_.dir)) {
    throw Error("--save-frames " + options_.dir.string() + ": cannot create the folder" +
                (ec ? " (" + ec.message() + ")" : std::string(" (a file of that name exists)")));
  }
  const std::vector<std::filesystem::path> earlier = earlier_frames(options_.dir);
  if (!earlier.empty() && !options_.replace) {
    throw Error("--save-frames " + options_.dir.string() + " holds " + std::to_string(earlier.size()) +
                " frames of an earlier run (" + earlier.front().filename().string() +
                ", ...); choose another folder or pass --force to replace them");
  }
  for (const std::filesystem::path& f : earlier) {
    if (!std::filesystem::remove(f, ec) && ec) {
      throw Error("--save-frames: cannot remove " + f.string() + " of an earlier run: " + ec.message());
    }
  }
  thread_ = std::thread([this] { run(); });
}

FrameSaver::~FrameSaver() { finish(); }

std::string FrameSaver::file_name(const FrameSnapshot& frame) const {
  char name[96];
  std::snprintf(name, sizeof(name), "frame_%06zu_%.6f.%s", frame.index, frame.timestamp, options_.format.c_str());
  return name;
}

void FrameSaver::offer(std::shared_ptr<const FrameSnapshot> frame) {
  if (!frame) return;
  const bool keep = offered_ % static_cast<std::size_t>(options_.every) == 0;
  ++offered_;
  if (!keep) return;
  // One producer: only the writer thread shrinks the queue, so a size below
  // capacity here means push() will not wait.
  if (!options_.wait_when_full && queue_.size() >= queue_.capacity()) {
    ++skipped_;
    return;
  }
  queue_.push(std::move(frame));
}

void FrameSaver::finish() {
  if (!thread_.joinable()) return;
  queue_.stop();
  thread_.join();
  if (skipped_ > 0) {
    spdlog::warn("--save-frames: {} frame(s) skipped while the writer was busy (--deterministic saves all)",
                 skipped_);
  }
}

void FrameSaver::run() {
  // Never leaves the loop early: with wait_when_full the run loop would wait forever.
  while (std::optional<std::shared_ptr<const FrameSnapshot>> frame = queue_.pop()) {
    Stopwatch watch;
    const std::filesystem::path path = options_.dir / file_name(**frame);
    bool ok = false;
    try {
      const cv::Mat image = draw_frame(**frame, options_.drawing);
      // PNG at OpenCV's default compression (1, its fastest).
      const std::vector<int> params =
          options_.format == "jpg" ? std::vector<int>{cv::IMWRITE_JPEG_QUALITY, 90} : std::vector<int>{};
      ok = !image.empty() && cv::imwrite(path.string(), image, params);
    } catch (const std::exception& e) {
      spdlog::warn("--save-frames: {}: {}", path.string(), e.what());
    }
    if (ok) {
      ++written_;
      write_ms_ += watch.elapsed_ms();
    } else {
      if (failed_ == 0) spdlog::warn("--save-frames: cannot write {}; check the folder is writable", path.string());
      ++failed_;
    }
  }
}

}  // namespace stillslam::apps
