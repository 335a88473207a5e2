#include "ctmap/io/image_bytes.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

std::uint32_t be16(const std::string& b, std::size_t at) {
    return (std::uint32_t((unsigned char)b[at]) << 8) | (unsigned char)b[at + 1];
}

std::uint32_t be32(const std::string& b, std::size_t at) { return (be16(b, at) << 16) | be16(b, at + 2); }

std::string without_empty_idat(const std::string& b, const std::string& name) {
    std::string out = b.substr(0, 8);
    std::size_t at = 8;
    // A chunk is length, type, data, CRC. stb_image acts on a header whose data and CRC are
    // missing too (a fuzz finding: the last 11 bytes of a file declaring a 1 GB IDAT).
    while (at + 8 <= b.size()) {
        const std::uint32_t len = be32(b, at);
        const bool idat = b.compare(at + 4, 4, "IDAT") == 0;
        const std::size_t follow = b.size() - at - 8;  // bytes after the header: data and CRC
        // stb_image grows its IDAT buffer to the declared length before it reads the bytes: a
        // 1 KB file declaring a 1 GB IDAT made it allocate 2 GB (fuzz finding). A data chunk
        // longer than what the file holds is refused here.
        if (idat && len > follow)
            throw BadInput(name, "corrupt PNG: an IDAT chunk declares " + std::to_string(len) + " bytes, but only " +
                                     std::to_string(follow) + " follow");
        if (idat && len == 0) {  // dropped, also when its CRC is cut off (stb_image would read it)
            at = std::min(b.size(), at + 12);
            continue;
        }
        if (follow < 4 || len > follow - 4) break;  // truncated or corrupt: leave the rest to stb_image
        out.append(b, at, 12 + std::size_t(len));
        const bool end = b.compare(at + 4, 4, "IEND") == 0;  // stb_image reads no further
        at += 12 + std::size_t(len);
        if (end) break;
    }
    out.append(b, at, std::string::npos);
    return out;
}

}  // namespace

std::string image_format(const std::string& b) {
    if (b.size() >= 8 && std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "PNG";
    if (b.size() >= 3 && (unsigned char)b[0] == 0xFF && (unsigned char)b[1] == 0xD8 && (unsigned char)b[2] == 0xFF)
        return "JPEG";
    return {};
}

std::string sanitized_image_bytes(const std::string& bytes, const std::string& name) {
    const std::string format = image_format(bytes);
    if (format == "PNG") return without_empty_idat(bytes, name);
    return bytes;
}

}  // namespace ctmap
