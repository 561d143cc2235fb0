#pragma once
// Internal to settings/: reads the keys of one section ("Tracking": keys
// Tracking.x, or x nested under a "Tracking:" map) into Options fields, and
// reports errors under the full dotted key whichever layout the file uses.
// Each read binds the key to the Options field it fills, so a failed
// check() (an OptionError naming the field) is reported as the YAML key.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core/persistence.hpp>

#include "stillslam/io/yaml_reader.h"

namespace stillslam {

// The values a key may take, [min, max] or (min, max]: what a sane
// configuration can be, checked as the key is read (the Options' own
// check() then adds what relates two fields).
struct Limits {
  double min, max;
  bool open_min = false;
  std::string text() const;  // "[1, 100]" or "(0, 100]"
};

// Thread-count keys: [min, max_threads()] (settings.h).
Limits thread_limits(double min);

class SectionKeys {
 public:
  // own: a section stillslam defines (Segmentation, Tracking, LocalMapping,
  // LoopClosing): reject_unknown_keys() applies and the nested layout is
  // read. Not own (ORBextractor, Stereo, Viewer): ORB-SLAM3 has keys there
  // that stillslam does not read; only flat keys are looked at.
  SectionKeys(const YamlReader& yaml, std::string section, bool own);

  const YamlReader& yaml() const { return yaml_; }
  std::string key(const std::string& name) const { return section_ + "." + name; }

  // The key's node (none when absent); `name` becomes a known key.
  cv::FileNode node(const std::string& name);
  // Read an optional key into `target` (unchanged when absent) and bind it
  // to `field` ("TrackerOptions.min_local_map_inliers"). A value outside
  // `limits` is an error "key 'X' is V: must be in [min, max]".
  void flag(const std::string& name, bool& target, const std::string& field = "");  // 0 or 1
  void integer(const std::string& name, int& target, const std::string& field, const Limits& limits);
  void count(const std::string& name, std::size_t& target, const std::string& field, const Limits& limits);
  void number(const std::string& name, double& target, const std::string& field, const Limits& limits);
  void number(const std::string& name, float& target, const std::string& field, const Limits& limits);

  [[noreturn]] void fail(const std::string& name, const std::string& message) const;

  // Runs `check` (Options::check() calls). An OptionError for a field bound
  // since the previous check() is reported under its key with the file's
  // value; any other as "<file>: <message>".
  void check(const std::function<void()>& check);

  // For own sections: a key of the section that no read above named is an
  // error listing the known keys.
  void reject_unknown_keys() const;

 private:
  cv::FileNode find(const std::string& name) const;  // flat, then nested
  std::optional<double> read_number(const std::string& name, const std::string& field,
                                    const std::optional<Limits>& limits);

  const YamlReader& yaml_;
  std::string section_;
  bool own_;
  cv::FileNode nested_;
  std::vector<std::string> known_;
  std::vector<std::pair<std::string, std::string>> bound_;  // (field, name) since the last check()
};

}  // namespace stillslam
