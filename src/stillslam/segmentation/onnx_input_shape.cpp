#include "stillslam/segmentation/onnx_input_shape.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <optional>
#include <string_view>

#include "stillslam/core/error.h"

namespace stillslam {
namespace {

// Just enough of the protobuf wire format to walk an ONNX ModelProto.
struct Field {
  std::uint32_t number = 0;
  std::uint32_t wire_type = 0;
  std::uint64_t varint = 0;  // wire type 0
  std::string_view bytes;    // wire type 2
};

class WireReader {
 public:
  explicit WireReader(std::string_view data) : data_(data) {}

  // Next field, nullopt at the end; throws std::runtime_error on malformed data.
  std::optional<Field> next() {
    if (pos_ >= data_.size()) return std::nullopt;
    Field f;
    const std::uint64_t key = varint();
    f.number = static_cast<std::uint32_t>(key >> 3);
    f.wire_type = static_cast<std::uint32_t>(key & 7);
    switch (f.wire_type) {
      case 0: f.varint = varint(); break;
      case 1: skip(8); break;
      case 2: {
        const std::uint64_t n = varint();
        if (n > data_.size() - pos_) throw std::runtime_error("length past the end");
        f.bytes = data_.substr(pos_, static_cast<std::size_t>(n));
        pos_ += static_cast<std::size_t>(n);
        break;
      }
      case 5: skip(4); break;
      default: throw std::runtime_error("unsupported wire type");
    }
    if (f.number == 0) throw std::runtime_error("field number 0");
    return f;
  }

 private:
  std::uint64_t varint() {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (pos_ >= data_.size()) throw std::runtime_error("truncated varint");
      const auto b = static_cast<unsigned char>(data_[pos_++]);
      v |= static_cast<std::uint64_t>(b & 0x7f) << shift;
      if ((b & 0x80) == 0) return v;
    }
    throw std::runtime_error("varint too long");
  }
  void skip(std::size_t n) {
    if (n > data_.size() - pos_) throw std::runtime_error("fixed field past the end");
    pos_ += n;
  }

  std::string_view data_;
  std::size_t pos_ = 0;
};

std::optional<std::string_view> first_field(std::string_view message, std::uint32_t number) {
  WireReader r(message);
  while (auto f = r.next())
    if (f->number == number && f->wire_type == 2) return f->bytes;
  return std::nullopt;
}

std::string_view value_info_name(std::string_view value_info) {
  return first_field(value_info, 1).value_or(std::string_view{});
}

std::vector<std::int64_t> shape_of(std::string_view value_info) {
  const auto type = first_field(value_info, 2);            // ValueInfoProto.type
  const auto tensor = type ? first_field(*type, 1) : std::nullopt;    // TypeProto.tensor_type
  const auto shape = tensor ? first_field(*tensor, 2) : std::nullopt;  // Tensor.shape
  if (!shape) throw std::runtime_error("graph input has no tensor shape");
  std::vector<std::int64_t> dims;
  WireReader r(*shape);
  while (auto dim = r.next()) {
    if (dim->number != 1 || dim->wire_type != 2) continue;  // TensorShapeProto.dim
    std::int64_t value = -1;                               // dim_param (symbolic) -> -1
    WireReader d(dim->bytes);
    while (auto df = d.next())
      if (df->number == 1 && df->wire_type == 0) value = static_cast<std::int64_t>(df->varint);
    dims.push_back(value);
  }
  return dims;
}

}  // namespace

std::vector<std::int64_t> onnx_input_shape(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open model file '" + path + "': check Segmentation.model / --model");
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    const auto graph = first_field(data, 7);  // ModelProto.graph
    if (!graph) throw std::runtime_error("no graph");
    std::vector<std::string_view> initializers;  // old exports list weights as inputs too
    std::vector<std::string_view> inputs;
    WireReader r(*graph);
    while (auto f = r.next()) {
      if (f->wire_type != 2) continue;
      if (f->number == 5) initializers.push_back(first_field(f->bytes, 8).value_or(std::string_view{}));
      if (f->number == 11) inputs.push_back(f->bytes);
    }
    for (const auto& input : inputs) {
      const auto name = value_info_name(input);
      if (std::find(initializers.begin(), initializers.end(), name) == initializers.end()) return shape_of(input);
    }
    throw std::runtime_error("graph has no input");
  } catch (const std::runtime_error& e) {
    throw Error("model file '" + path + "' is not a readable ONNX model (" + e.what() +
                "): export the segmentation model to ONNX (see models/README.md)");
  }
}

}  // namespace stillslam
