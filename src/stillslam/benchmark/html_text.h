#pragma once
// Text helpers for the self-contained HTML run report (html_escape comes from
// core/text.h): images inlined as data URIs, SVG inlined (the report loads
// nothing from outside).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stillslam/core/text.h"  // html_escape

namespace stillslam {

// "data:<mime>;base64,..." for an <img src>.
std::string data_uri(const std::string& mime, const std::vector<std::uint8_t>& bytes);

// An SVG document (as render_line_plot writes) without its XML declaration,
// ready to sit inline in HTML.
std::string inline_svg(const std::string& svg);

}  // namespace stillslam
