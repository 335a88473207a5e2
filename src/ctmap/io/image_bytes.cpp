#include "ctmap/io/image_bytes.h"

#include <cstdint>
#include <algorithm>
#include <cstring>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

std::uint32_t be16(const std::string& b, std::size_t at) {
    return (std::uint32_t((unsigned char)b[at]) << 8) | (unsigned char)b[at + 1];
}

std::uint32_t be32(const std::string& b, std::size_t at) { return (be16(b, at) << 16) | be16(b, at + 2); }

/// Each table of a DHT segment: a class/id byte, 16 code counts, then that many symbols; the
/// counts of one table sum to at most 256 (ITU T.81 B.2.4.2).
void check_huffman_segment(const std::string& b, std::size_t from, std::size_t to, const std::string& name) {
    std::size_t at = from;
    // stb_image reads tables while any byte of the segment is left: a table may start at its last
    // byte (and read its counts past the end).
    while (at < to) {
        std::uint32_t sum = 0;
        // stb_image reads all 16 counts of a table that starts in the segment, even past its end.
        for (std::size_t i = 0; i < 16 && at + 1 + i < b.size(); ++i) sum += (unsigned char)b[at + 1 + i];
        if (sum > 256)
            throw BadInput(name, "corrupt JPEG: a Huffman table declares " + std::to_string(sum) +
                                     " codes (at most 256)");
        at += 17 + sum;
    }
}

void check_jpeg(const std::string& b, const std::string& name) {
    std::size_t at = 2;  // after SOI
    while (at + 4 <= b.size()) {
        if ((unsigned char)b[at] != 0xFF) {  // entropy-coded data after a scan: find the next marker
            ++at;
            continue;
        }
        const unsigned char m = (unsigned char)b[at + 1];
        if (m == 0xFF || m == 0x00 || (m >= 0xD0 && m <= 0xD7) || m == 0x01) {  // fill, stuffing, RSTn, TEM
            at += m == 0xFF ? 1 : 2;
            continue;
        }
        if (m == 0xD9) return;  // EOI
        const std::size_t len = be16(b, at + 2);
        // A truncated table is still read by stb_image (as zeros past the end): check what is there.
        if (m == 0xC4) check_huffman_segment(b, at + 4, std::min(at + 2 + len, b.size()), name);
        if (len < 2 || at + 2 + len > b.size()) return;  // truncated: stb_image reports it
        at += 2 + len;
    }
}

std::string without_empty_idat(const std::string& b, const std::string& name) {
    std::string out = b.substr(0, 8);
    std::size_t at = 8;
    while (at + 12 <= b.size()) {
        const std::uint32_t len = be32(b, at);
        const bool idat = b.compare(at + 4, 4, "IDAT") == 0;
        // stb_image grows its IDAT buffer to the declared length before it reads the bytes: a
        // 1 KB file declaring a 1 GB IDAT made it allocate 2 GB (fuzz finding). A data chunk
        // longer than what the file holds is refused here.
        if (idat && len > b.size() - at - 12)
            throw BadInput(name, "corrupt PNG: an IDAT chunk declares " + std::to_string(len) + " bytes, but only " +
                                     std::to_string(b.size() - at - 12) + " follow");
        if (len > b.size() - at - 12) break;  // truncated or corrupt: leave the rest to stb_image
        if (!(len == 0 && idat)) out.append(b, at, 12 + std::size_t(len));
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
    if (format == "JPEG") {
        check_jpeg(bytes, name);
        return bytes;
    }
    if (format == "PNG") return without_empty_idat(bytes, name);
    return bytes;
}

}  // namespace ctmap
