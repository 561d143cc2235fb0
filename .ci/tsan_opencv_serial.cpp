// Linked into the ThreadSanitizer test executables only (scripts/check-variants
// tsan). Debian's OpenCV runs cv::parallel_for_ bodies on TBB worker threads;
// libtbb is not instrumented, so TSan sees neither the hand-off of a body to
// a worker nor the join and reports every access a body makes (or the caller
// makes afterwards) as a race. With OpenCV's threads off before main() the
// bodies run on the calling thread, and the run checks stillslam's own
// threads (tracking, local mapping, loop closing, segmentation).
#include <opencv2/core/utility.hpp>

namespace {

const int opencv_serial = (cv::setNumThreads(0), 0);

}  // namespace
