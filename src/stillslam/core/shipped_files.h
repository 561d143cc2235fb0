#pragma once
// Files that ship in the repository (vocab/orb_vocabulary.bin,
// models/yolo11n-seg_384x512.onnx) are found from the running executable:
// next to it and in its parent folders (build/stillslam -> <repo>/vocab/).
#include <unistd.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>

namespace stillslam {

inline constexpr const char* kShippedVocabulary = "vocab/orb_vocabulary.bin";
inline constexpr const char* kShippedSegmentationModel = "models/yolo11n-seg_384x512.onnx";

// `relative` (e.g. kShippedVocabulary) in the folder of `executable` or the
// nearest parent folder that has it; nullopt when none has.
inline std::optional<std::filesystem::path> find_shipped_file(const std::filesystem::path& executable,
                                                              const std::filesystem::path& relative) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::path dir = executable.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    const fs::path candidate = dir / relative;
    if (fs::is_regular_file(candidate, ec)) return candidate;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

// The running executable (/proc/self/exe); empty when it cannot be read.
inline std::filesystem::path running_executable() {
  std::array<char, 4096> buffer{};
  const ssize_t n = readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  return n > 0 ? std::filesystem::path(std::string(buffer.data(), static_cast<std::size_t>(n)))
               : std::filesystem::path();
}

}  // namespace stillslam
