#pragma once
// Typed, validated access to an OpenCV FileStorage YAML file (the format of
// ORB-SLAM3 settings and EuRoC sensor.yaml). Every failure is a
// stillslam::Error naming the file and the key.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/persistence.hpp>

namespace stillslam {

class YamlReader {
 public:
  // Throws Error when the file is missing or is not valid OpenCV YAML.
  explicit YamlReader(const std::filesystem::path& file);

  const std::filesystem::path& file() const { return file_; }
  bool has(const std::string& key) const;
  // Top-level key names in file order (nested maps are not expanded).
  std::vector<std::string> keys() const;
  cv::FileNode node(const std::string& key) const { return storage_[key]; }

  double number(const std::string& key) const;  // required
  std::optional<double> optional_number(const std::string& key) const;
  int integer(const std::string& key) const;  // required, must be integral
  std::optional<int> optional_integer(const std::string& key) const;
  std::optional<std::string> optional_string(const std::string& key) const;
  // A matrix given as !!opencv-matrix or as a plain {rows, cols, data} map.
  std::optional<Eigen::MatrixXd> optional_matrix(const std::string& key) const;
  // A flat numeric sequence ([a, b, c]).
  std::optional<std::vector<double>> optional_numbers(const std::string& key) const;

  // "<file>: key '<key>' <message>" as an Error, for callers' own checks.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  std::filesystem::path file_;
  cv::FileStorage storage_;
};

// Number stored in a node (int or real); nullopt for strings, maps, sequences.
std::optional<double> node_number(const cv::FileNode& node);

}  // namespace stillslam
