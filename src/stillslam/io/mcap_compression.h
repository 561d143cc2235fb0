#pragma once
// Chunk compression of MCAP files: "" (none), "zstd" (libzstd) and "lz4"
// (the LZ4 frame format, liblz4). Errors name `what` (file and chunk offset).
#include <cstdint>
#include <string>

namespace stillslam {

std::string mcap_compress(const std::string& compression, const std::string& data);
std::string mcap_decompress(const std::string& compression, const char* data, std::size_t size,
                            std::size_t uncompressed_size, const std::string& what);
// CRC-32 (zlib's) of the uncompressed chunk records, as the Chunk record stores it.
std::uint32_t mcap_crc32(const std::string& data);
// Whether `compression` is one of "", "none", "zstd", "lz4".
bool mcap_compression_known(const std::string& compression);

}  // namespace stillslam
