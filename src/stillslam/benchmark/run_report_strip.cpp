// The strip of saved frames in the HTML run report (run_report_parts.h): the
// annotated frames `stillslam run --save-frames` wrote, evenly spaced,
// shrunk and inlined as JPEG data URIs.
#include <spdlog/spdlog.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/benchmark/html_text.h"
#include "stillslam/benchmark/run_report_parts.h"

namespace stillslam {

std::string report_frame_strip(const ReportRun& run, int count, int width) {
  const std::size_t n = run.saved_frames.size();
  if (n == 0 || count <= 0) return {};
  const std::size_t shown = std::min<std::size_t>(n, static_cast<std::size_t>(count));
  std::string html = "<div class=\"strip\">";
  for (std::size_t k = 0; k < shown; ++k) {
    // First and last included: k * (n - 1) / (shown - 1).
    const std::size_t i = shown == 1 ? 0 : k * (n - 1) / (shown - 1);
    const std::filesystem::path& file = run.saved_frames[i];
    const cv::Mat image = cv::imread(file.string(), cv::IMREAD_COLOR);
    if (image.empty()) {
      spdlog::warn("report: cannot read the saved frame {}; left out of the strip", file.string());
      continue;
    }
    cv::Mat small = image;
    if (image.cols > width) {
      cv::resize(image, small, cv::Size(width, std::max(1, image.rows * width / image.cols)), 0, 0, cv::INTER_AREA);
    }
    std::vector<std::uint8_t> jpeg;
    cv::imencode(".jpg", small, jpeg, {cv::IMWRITE_JPEG_QUALITY, 80});
    html += "<figure><img class=\"frame\" alt=\"" + html_escape(file.filename().string()) + "\" src=\"" +
            data_uri("image/jpeg", jpeg) + "\"><figcaption>" + html_escape(file.stem().string()) +
            "</figcaption></figure>";
  }
  return html + "</div>";
}

}  // namespace stillslam
