#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace stillslam {

// Dimensions of the first graph input of an ONNX file (e.g. {1, 3, 384, 512}),
// read directly from the protobuf (ModelProto.graph.input[0].type.tensor_type.shape)
// because OpenCV DNN does not expose it. Symbolic dimensions are returned as -1.
// Throws stillslam::Error naming the file when it is missing or not an ONNX model.
std::vector<std::int64_t> onnx_input_shape(const std::string& path);

}  // namespace stillslam
