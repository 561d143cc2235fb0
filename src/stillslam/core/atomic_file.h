#pragma once
// Whole-file writes that never leave a cut file: the bytes go to a temporary
// file in the same folder, which is synced, closed and only then renamed over
// the target. On any failure the temporary file is removed, the target keeps
// its old content (or stays absent) and an Error names the file and the
// system's reason (e.g. "No space left on device").
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "stillslam/core/error.h"

namespace stillslam {

// The reason for errno value `err`, e.g. "No space left on device".
inline std::string system_reason(int err) { return std::error_code(err, std::generic_category()).message(); }

// `path` + ".tmp-<pid>-<n>": unique per process and call, next to the target
// so the rename stays within one file system.
inline std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return tmp;
}

// `kind` names what the file is in the message ("cannot write map file X: ...").
inline void write_file_atomically(const std::filesystem::path& path, std::string_view bytes,
                                  std::string_view kind = {}) {
  const std::string what = "cannot write " + (kind.empty() ? std::string() : std::string(kind) + " ") + path.string();
  const std::filesystem::path tmp = temporary_path_for(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw Error(what + ": " + system_reason(errno) + "; check that its folder exists and is writable");
  auto fail = [&](int err, bool close_fd) {
    if (close_fd) ::close(fd);
    ::unlink(tmp.c_str());
    throw Error(what + ": " + system_reason(err));
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(n < 0 ? errno : ENOSPC, true);
    done += static_cast<std::size_t>(n);
  }
  // Some file systems report a full disk only when the data reaches it.
  if (::fsync(fd) != 0) fail(errno, true);
  if (::close(fd) != 0) fail(errno, false);
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(errno, false);
}

}  // namespace stillslam
