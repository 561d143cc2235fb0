#pragma once
// Writes tiny but valid ONNX files (one Relu node) for error-path tests, encoding
// the protobuf by hand so the tests need no ONNX tooling.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace stillslam::test {

class Proto {
 public:
  Proto& varint(int field, std::uint64_t v) {
    key(field, 0);
    raw_varint(v);
    return *this;
  }
  Proto& bytes(int field, const std::string& s) {
    key(field, 2);
    raw_varint(s.size());
    out_ += s;
    return *this;
  }
  Proto& message(int field, const Proto& m) { return bytes(field, m.out_); }
  const std::string& str() const { return out_; }

 private:
  void key(int field, int wire) { raw_varint(static_cast<std::uint64_t>(field) << 3 | static_cast<std::uint64_t>(wire)); }
  void raw_varint(std::uint64_t v) {
    do {
      unsigned char b = v & 0x7f;
      v >>= 7;
      if (v) b |= 0x80;
      out_.push_back(static_cast<char>(b));
    } while (v);
  }
  std::string out_;
};

inline Proto value_info(const std::string& name, const std::vector<std::int64_t>& dims) {
  Proto shape;
  for (auto d : dims) shape.message(1, Proto().varint(1, static_cast<std::uint64_t>(d)));  // dim.dim_value
  const Proto tensor = Proto().varint(1, 1).message(2, shape);                               // float, shape
  return Proto().bytes(1, name).message(2, Proto().message(1, tensor));
}

// y = Relu(x), x and y of shape dims.
inline void write_relu_onnx(const std::string& path, const std::vector<std::int64_t>& dims) {
  const Proto node = Proto().bytes(1, "x").bytes(2, "y").bytes(3, "relu").bytes(4, "Relu");
  const Proto graph = Proto().message(1, node).bytes(2, "g").message(11, value_info("x", dims)).message(
      12, value_info("y", dims));
  const Proto model = Proto().varint(1, 7).message(7, graph).message(8, Proto().bytes(1, "").varint(2, 13));
  std::ofstream(path, std::ios::binary) << model.str();
}

}  // namespace stillslam::test
