#pragma once
// Chunk compression of MCAP files: "" (none), "zstd" (libzstd) and "lz4"
// (the LZ4 frame format, liblz4). Errors name `what` (file and chunk offset).
#include <string>

namespace stillslam {

std::string mcap_compress(const std::string& compression, const std::string& data);
std::string mcap_decompress(const std::string& compression, const char* data, std::size_t size,
                            std::size_t uncompressed_size, const std::string& what);
// Whether `compression` is one of "", "none", "zstd", "lz4".
bool mcap_compression_known(const std::string& compression);

}  // namespace stillslam
