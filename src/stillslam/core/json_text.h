#pragma once
// JSON text that never throws on strings from outside (paths, messages):
// bytes that are not UTF-8, such as a Latin-1 folder name, become U+FFFD
// instead of nlohmann::json's type_error 316 ("incomplete UTF-8 string").
#include <nlohmann/json.hpp>
#include <string>

namespace stillslam {

// json.dump(indent) with invalid UTF-8 replaced; -1 gives one line.
inline std::string json_text(const nlohmann::json& json, int indent = -1) {
  return json.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace stillslam
