#include "stillslam/io/mcap_compression.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <memory>

#include "stillslam/core/error.h"

namespace stillslam {

std::uint32_t mcap_crc32(const std::string& data) {
  uLong crc = crc32(0L, Z_NULL, 0);
  std::size_t done = 0;
  while (done < data.size()) {  // zlib takes uInt lengths
    const std::size_t n = std::min<std::size_t>(data.size() - done, 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(data.data() + done), static_cast<uInt>(n));
    done += n;
  }
  return static_cast<std::uint32_t>(crc);
}

bool mcap_compression_known(const std::string& c) { return c.empty() || c == "none" || c == "zstd" || c == "lz4"; }

std::string mcap_compress(const std::string& compression, const std::string& data) {
  if (compression.empty() || compression == "none") return data;
  std::string out;
  if (compression == "zstd") {
    out.resize(ZSTD_compressBound(data.size()));
    const std::size_t n = ZSTD_compress(out.data(), out.size(), data.data(), data.size(), 3);
    if (ZSTD_isError(n)) throw Error(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
    out.resize(n);
    return out;
  }
  if (compression == "lz4") {
    out.resize(LZ4F_compressFrameBound(data.size(), nullptr));
    const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), nullptr);
    if (LZ4F_isError(n)) throw Error(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
    out.resize(n);
    return out;
  }
  throw Error("MCAP compression '" + compression + "' is not supported (use zstd, lz4 or none)");
}

std::string mcap_decompress(const std::string& compression, const char* data, std::size_t size,
                            std::size_t uncompressed_size, const std::string& what) {
  if (compression.empty() || compression == "none") {
    if (size != uncompressed_size) {
      throw Error(what + ": uncompressed chunk holds " + std::to_string(size) + " bytes, its header says " +
                  std::to_string(uncompressed_size));
    }
    return std::string(data, size);
  }
  // A corrupt size must not become a huge allocation: zstd frames state their
  // content size; lz4 cannot expand more than 255:1.
  if (compression == "zstd") {
    const unsigned long long declared = ZSTD_getFrameContentSize(data, size);
    if (declared == ZSTD_CONTENTSIZE_ERROR) throw Error(what + ": zstd chunk is corrupt (no zstd frame header)");
    if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != uncompressed_size) {
      throw Error(what + ": zstd chunk holds " + std::to_string(declared) + " bytes, its header says " +
                  std::to_string(uncompressed_size));
    }
    if (declared == ZSTD_CONTENTSIZE_UNKNOWN && uncompressed_size > (std::size_t{1} << 30)) {
      throw Error(what + ": chunk claims " + std::to_string(uncompressed_size) + " bytes uncompressed (over 1 GiB)");
    }
  } else if (compression == "lz4" && uncompressed_size / 256 > size + 65536) {
    throw Error(what + ": lz4 chunk of " + std::to_string(size) + " bytes cannot hold the " +
                std::to_string(uncompressed_size) + " bytes its header says");
  }
  std::string out(uncompressed_size, '\0');
  if (compression == "zstd") {
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), data, size);
    if (ZSTD_isError(n) || n != uncompressed_size) {
      throw Error(what + ": zstd chunk does not decompress to its " + std::to_string(uncompressed_size) + " bytes" +
                  (ZSTD_isError(n) ? std::string(" (") + ZSTD_getErrorName(n) + ")" : std::string()));
    }
    return out;
  }
  if (compression == "lz4") {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw Error(what + ": lz4 context failed");
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(raw, &LZ4F_freeDecompressionContext);
    std::size_t in_pos = 0, out_pos = 0;
    while (in_pos < size) {
      std::size_t in_n = size - in_pos, out_n = out.size() - out_pos;
      const std::size_t rc = LZ4F_decompress(ctx.get(), out.data() + out_pos, &out_n, data + in_pos, &in_n, nullptr);
      if (LZ4F_isError(rc)) throw Error(what + ": lz4 chunk is corrupt (" + LZ4F_getErrorName(rc) + ")");
      in_pos += in_n;
      out_pos += out_n;
      if (rc == 0) break;  // frame complete
      if (in_n == 0 && out_n == 0) break;
    }
    if (out_pos != uncompressed_size) {
      throw Error(what + ": lz4 chunk decompresses to " + std::to_string(out_pos) + " bytes, its header says " +
                  std::to_string(uncompressed_size));
    }
    return out;
  }
  throw Error(what + ": chunk compression '" + compression + "' is not supported (zstd, lz4 or none)");
}

}  // namespace stillslam
