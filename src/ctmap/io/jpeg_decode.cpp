#include "ctmap/io/jpeg_decode.h"

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include <jpeglib.h>
#include <jerror.h>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

/// libjpeg reports errors through `error_exit`, which must not return: it jumps back to the
/// setjmp in `run` (the libjpeg way; unwinding a C++ exception through libjpeg's C frames is not
/// allowed). Nothing with a destructor lives in `run`'s frame.
struct ErrorManager {
    jpeg_error_mgr pub;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

constexpr int kMaxScans = 500;

[[noreturn]] void on_error(j_common_ptr cinfo) {
    auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, err->message);
    std::longjmp(err->jump, 1);
}

/// Warnings (level -1) are corrupt data libjpeg would decode anyway (grey for a truncated file):
/// refused, but for stray bytes between segments, which real cameras write.
void on_message(j_common_ptr cinfo, int level) {
    if (level >= 0 || cinfo->err->msg_code == JWRN_EXTRANEOUS_DATA) return;
    on_error(cinfo);
}

void on_progress(j_common_ptr cinfo) {
    auto* d = reinterpret_cast<j_decompress_ptr>(cinfo);
    if (d->input_scan_number > kMaxScans) {
        cinfo->err->msg_code = JERR_NOT_COMPILED;  // any code: the message is ours
        auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
        std::snprintf(err->message, sizeof err->message, "more than %d scans (a crafted progressive file)",
                      kMaxScans);
        std::longjmp(err->jump, 1);
    }
}

/// Reads the header and, with `pixels`, every scanline as RGBA. Returns false with libjpeg's
/// reason in `err.message`. `pixels` lives in the caller's frame (longjmp skips no destructor).
bool run(const std::string& bytes, ErrorManager& err, int& width, int& height, std::vector<std::uint8_t>* pixels) {
    jpeg_decompress_struct cinfo;
    jpeg_progress_mgr progress;
    std::memset(&cinfo, 0, sizeof cinfo);  // jpeg_destroy_decompress is safe on it before creation
    cinfo.err = jpeg_std_error(&err.pub);
    err.pub.error_exit = on_error;
    err.pub.emit_message = on_message;
    err.message[0] = '\0';
    if (setjmp(err.jump)) {
        jpeg_destroy_decompress(&cinfo);
        return false;
    }
    jpeg_create_decompress(&cinfo);
    progress.progress_monitor = on_progress;
    cinfo.progress = &progress;
    jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&cinfo, TRUE);
    width = int(cinfo.image_width);
    height = int(cinfo.image_height);
    if (!pixels) {
        jpeg_destroy_decompress(&cinfo);
        return true;
    }
    const bool cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
    // Adobe's CMYK JPEGs (nearly all of them) store inverted ink values.
    const bool inverted = cinfo.saw_Adobe_marker;
    cinfo.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    jpeg_start_decompress(&cinfo);
    pixels->assign(std::size_t(width) * height * 4, 0);
    while (cinfo.output_scanline < cinfo.output_height) {
        JSAMPROW row = pixels->data() + std::size_t(cinfo.output_scanline) * width * 4;
        jpeg_read_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_decompress(&cinfo);
    jpeg_destroy_decompress(&cinfo);
    if (cmyk)
        for (std::size_t i = 0; i < pixels->size(); i += 4) {
            std::uint8_t* p = pixels->data() + i;
            const int k = inverted ? p[3] : 255 - p[3];
            for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(((inverted ? p[c] : 255 - p[c]) * k + 127) / 255);
            p[3] = 255;
        }
    return true;
}

}  // namespace

void read_jpeg_size(const std::string& bytes, const std::string& name, int& width, int& height) {
    ErrorManager err;
    if (!run(bytes, err, width, height, nullptr))
        throw BadInput(name, std::string("the JPEG header is truncated or corrupt (") + err.message + ")");
}

std::vector<std::uint8_t> decode_jpeg_rgba(const std::string& bytes, const std::string& name, int& width,
                                           int& height) {
    ErrorManager err;
    std::vector<std::uint8_t> pixels;
    if (!run(bytes, err, width, height, &pixels))
        throw BadInput(name, std::string("the JPEG image data is truncated or corrupt (") + err.message + ")");
    return pixels;
}

}  // namespace ctmap
