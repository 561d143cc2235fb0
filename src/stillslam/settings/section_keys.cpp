#include "stillslam/settings/section_keys.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "stillslam/core/option_check.h"
#include "stillslam/settings/settings.h"

namespace stillslam {

std::string Limits::text() const {
  return (open_min ? "(" : "[") + option_check::text(min) + ", " + option_check::text(max) + "]";
}

int max_threads() { return std::max(64, 4 * static_cast<int>(std::thread::hardware_concurrency())); }

Limits thread_limits(double min) { return {min, static_cast<double>(max_threads())}; }

SectionKeys::SectionKeys(const YamlReader& yaml, std::string section, bool own)
    : yaml_(yaml), section_(std::move(section)), own_(own) {
  if (!own_) return;
  nested_ = yaml_.node(section_);
  if (!nested_.isNone() && !nested_.isMap()) {
    yaml_.fail(section_, "must be a map of " + section_ + " settings or absent");
  }
}

cv::FileNode SectionKeys::node(const std::string& name) {
  if (std::find(known_.begin(), known_.end(), name) == known_.end()) known_.push_back(name);
  return find(name);
}

cv::FileNode SectionKeys::find(const std::string& name) const {
  const cv::FileNode flat = yaml_.node(key(name));
  if (!flat.isNone()) return flat;
  return nested_.isMap() ? nested_[name] : cv::FileNode();
}

std::optional<double> SectionKeys::read_number(const std::string& name, const std::string& field,
                                              const std::optional<Limits>& limits) {
  if (!field.empty()) bound_.emplace_back(field, name);
  const cv::FileNode n = node(name);
  if (n.isNone()) return std::nullopt;
  const auto v = node_number(n);
  if (!v || !std::isfinite(*v)) fail(name, "must be a number");
  if (limits && !((limits->open_min ? *v > limits->min : *v >= limits->min) && *v <= limits->max)) {
    fail(name, "is " + option_check::text(*v) + ": must be in " + limits->text());
  }
  return v;
}

void SectionKeys::flag(const std::string& name, bool& target, const std::string& field) {
  const auto v = read_number(name, field, std::nullopt);
  if (!v) return;
  if (*v != 0 && *v != 1) fail(name, "must be 0 or 1");
  target = *v == 1;
}

void SectionKeys::integer(const std::string& name, int& target, const std::string& field, const Limits& limits) {
  const auto v = read_number(name, field, limits);
  if (!v) return;
  if (std::round(*v) != *v || std::abs(*v) > 2e9) fail(name, "must be an integer");
  target = static_cast<int>(*v);
}

void SectionKeys::count(const std::string& name, std::size_t& target, const std::string& field,
                        const Limits& limits) {
  const auto v = read_number(name, field, limits);
  if (!v) return;
  if (std::round(*v) != *v || *v < 0 || *v > 2e9) fail(name, "must be an integer >= 0");
  target = static_cast<std::size_t>(*v);
}

void SectionKeys::number(const std::string& name, double& target, const std::string& field, const Limits& limits) {
  if (const auto v = read_number(name, field, limits)) target = *v;
}

void SectionKeys::number(const std::string& name, float& target, const std::string& field, const Limits& limits) {
  if (const auto v = read_number(name, field, limits)) target = static_cast<float>(*v);
}

void SectionKeys::fail(const std::string& name, const std::string& message) const {
  yaml_.fail(key(name), message);
}

void SectionKeys::check(const std::function<void()>& check) {
  const auto bound = std::move(bound_);
  bound_.clear();
  try {
    check();
  } catch (const OptionError& e) {
    for (const auto& [field, name] : bound) {
      if (field != e.field()) continue;
      const auto v = node_number(find(name));
      fail(name, "is " + (v ? option_check::text(*v) : e.value()) + ": " + e.requirement());
    }
    throw Error(yaml_.file().string() + ": " + e.what());
  }
}

void SectionKeys::reject_unknown_keys() const {
  if (!own_) return;
  auto is_known = [&](const std::string& name) {
    return std::find(known_.begin(), known_.end(), name) != known_.end();
  };
  auto reject = [&](const std::string& name) {
    std::string list;
    for (const std::string& k : known_) list += (list.empty() ? "" : ", ") + key(k);
    fail(name, "is not a known " + section_ + " setting (known keys: " + list + ")");
  };
  const std::string prefix = section_ + ".";
  for (const std::string& k : yaml_.keys()) {
    if (k.rfind(prefix, 0) == 0 && !is_known(k.substr(prefix.size()))) reject(k.substr(prefix.size()));
  }
  if (nested_.isMap()) {
    for (auto it = nested_.begin(); it != nested_.end(); ++it) {
      if (!is_known((*it).name())) reject((*it).name());
    }
  }
}

}  // namespace stillslam
