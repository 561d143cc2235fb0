#include "stillslam/io/input_file.h"

#include <cerrno>
#include <cstring>
#include <iterator>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

namespace fs = std::filesystem;

constexpr char kUtf8Bom[] = "\xEF\xBB\xBF";

std::string named(const fs::path& path, const std::string& what) { return what + " " + path.string(); }

}  // namespace

std::ifstream open_input_file(const fs::path& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) {
    throw Error(named(path, what) + " does not exist; check the path");
  }
  if (status.type() == fs::file_type::directory) {
    throw Error(named(path, what) + " is a folder, expected a file; name the file inside it");
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    const std::string reason = error == EACCES ? "permission denied, check its permissions"
                               : error != 0    ? std::strerror(error)
                                               : "unknown reason";
    throw Error(named(path, what) + " cannot be read: " + reason);
  }
  char head[3] = {};
  in.read(head, 3);
  if (!(in.gcount() == 3 && std::memcmp(head, kUtf8Bom, 3) == 0)) {
    in.clear();
    in.seekg(0);
  }
  return in;
}

std::string read_input_file(const fs::path& path, const std::string& what) {
  std::ifstream in = open_input_file(path, what);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(named(path, what) + " cannot be read: an input error occurred while reading it");
  return text;
}

}  // namespace stillslam
