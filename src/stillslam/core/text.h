#pragma once
// Small text helpers shared by the readers of settings, lists and trajectories
// and by the HTML / SVG writers.
// One header, so no module keeps a file-local copy (two file-local copies
// collide when a unity build puts their files in one translation unit).
#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace stillslam {

// `s` without leading and trailing blanks (space, tab, CR, LF).
inline std::string trim(std::string_view s) {
  const auto begin = s.find_first_not_of(" \t\r\n");
  if (begin == std::string_view::npos) return {};
  const auto end = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(begin, end - begin + 1));
}

// `text` with & < > " ' as character references, for HTML and SVG text and
// attribute values.
inline std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// ASCII lower case.
inline std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Tokens separated by blanks, and also by commas when `commas` (blanks around
// commas are padding). Empty tokens are dropped.
inline std::vector<std::string> split_tokens(std::string_view text, bool commas) {
  std::vector<std::string> tokens;
  std::string current;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || (commas && c == ',')) {
      if (!current.empty()) tokens.push_back(current);
      current.clear();
    } else {
      current.push_back(c);
    }
  }
  if (!current.empty()) tokens.push_back(current);
  return tokens;
}

}  // namespace stillslam
