// JPEG photographs through libjpeg-turbo (io/jpeg_decode, issue 17): what stb_image decoded before
// still decodes (baseline, progressive, grey, Adobe CMYK), to the pixels of the source within
// JPEG's loss; what is corrupt is refused naming the file. The JPEGs are written here with
// libjpeg's own encoder, the source pixels are the oracle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ctmap/errors.h"
#include "ctmap/io/image.h"
#include "test_support.h"

#include <jpeglib.h>  // after <cstdio>: it uses FILE and size_t

namespace ctmap::test {
namespace {

enum class Scans { baseline, progressive, many };

/// `px` (w x h, `components` channels in `space`) as a JPEG at quality 95. `many`: a progressive
/// script of 576 valid scans (each component's DC and each of its 63 AC coefficients in three
/// successive-approximation passes).
std::string encode_jpeg(const std::vector<std::uint8_t>& px, int w, int h, int components, J_COLOR_SPACE space,
                        Scans scans) {
    jpeg_compress_struct c;
    jpeg_error_mgr err;
    c.err = jpeg_std_error(&err);
    jpeg_create_compress(&c);
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&c, &buffer, &size);
    c.image_width = JDIMENSION(w);
    c.image_height = JDIMENSION(h);
    c.input_components = components;
    c.in_color_space = space;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 95, TRUE);
    std::vector<jpeg_scan_info> script;
    if (scans == Scans::progressive) jpeg_simple_progression(&c);
    if (scans == Scans::many) {
        const int n = c.num_components;
        for (int pass = 0; pass < 3; ++pass)  // DC: Al 2, then 2 -> 1, then 1 -> 0
            for (int ci = 0; ci < n; ++ci) script.push_back({1, {ci}, 0, 0, pass == 0 ? 0 : 3 - pass, 2 - pass});
        for (int pass = 0; pass < 3; ++pass)
            for (int ci = 0; ci < n; ++ci)
                for (int k = 1; k < 64; ++k) script.push_back({1, {ci}, k, k, pass == 0 ? 0 : 3 - pass, 2 - pass});
        c.scan_info = script.data();
        c.num_scans = int(script.size());
    }
    jpeg_start_compress(&c, TRUE);
    while (c.next_scanline < c.image_height) {
        JSAMPROW row = const_cast<std::uint8_t*>(px.data()) + std::size_t(c.next_scanline) * w * components;
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    std::string out(reinterpret_cast<char*>(buffer), size);
    free(buffer);
    return out;
}

/// chelsea.png's RGB pixels.
std::vector<std::uint8_t> chelsea_rgb(int& w, int& h) {
    const Image png = read_image(data("images/chelsea.png"));
    w = png.width, h = png.height;
    std::vector<std::uint8_t> rgb(std::size_t(w) * h * 3);
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i)
        for (int k = 0; k < 3; ++k) rgb[i * 3 + k] = png.pixels[i * 4 + k];
    return rgb;
}

/// Mean absolute difference per channel between decoded RGBA and source RGB.
double mean_error(const Image& img, const std::vector<std::uint8_t>& rgb) {
    double sum = 0;
    for (std::size_t i = 0; i < rgb.size() / 3; ++i)
        for (int k = 0; k < 3; ++k) sum += std::abs(int(img.pixels[i * 4 + k]) - int(rgb[i * 3 + k]));
    return sum / double(rgb.size());
}

TEST(RoundTripJpeg, BaselineAndProgressivePhotosDecodeToTheirSourceWithinJpegLoss) {
    TempDir d;
    int w = 0, h = 0;
    const std::vector<std::uint8_t> rgb = chelsea_rgb(w, h);
    for (const Scans s : {Scans::baseline, Scans::progressive}) {
        const std::string file = d / (s == Scans::baseline ? "b.jpg" : "p.jpg");
        write_file(file, encode_jpeg(rgb, w, h, 3, JCS_RGB, s));
        const Image img = read_image(file);
        ASSERT_EQ(img.width, w);
        ASSERT_EQ(img.height, h);
        ASSERT_EQ(img.channels, 4);
        const double e = mean_error(img, rgb);
        std::printf("%s chelsea %d x %d, quality 95: mean error %.2f per channel\n",
                    s == Scans::baseline ? "baseline" : "progressive", w, h, e);
        EXPECT_LT(e, 3.0);  // quality 95 on a photograph: about 1-2 grey levels
        for (std::size_t i = 3; i < img.pixels.size(); i += 4) ASSERT_EQ(img.pixels[i], 255);
    }
}

TEST(RoundTripJpeg, GreyAndAdobeCmykJpegsDecodeToRgb) {
    TempDir d;
    const int w = 48, h = 32;
    // Grey: a horizontal ramp; every decoded pixel has r = g = b within JPEG loss of the ramp.
    std::vector<std::uint8_t> grey(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) grey[std::size_t(y) * w + x] = std::uint8_t(x * 255 / (w - 1));
    write_file(d / "g.jpg", encode_jpeg(grey, w, h, 1, JCS_GRAYSCALE, Scans::baseline));
    const Image g = read_image(d / "g.jpg");
    ASSERT_EQ(g.width, w);
    for (int i = 0; i < w * h; ++i) {
        ASSERT_EQ(g.pixels[i * 4], g.pixels[i * 4 + 1]);
        ASSERT_EQ(g.pixels[i * 4], g.pixels[i * 4 + 2]);
        ASSERT_LE(std::abs(int(g.pixels[i * 4]) - int(grey[i])), 8) << "pixel " << i;
    }
    // Adobe CMYK (inverted ink, as Photoshop writes): left half red ink-free (C=0 M=255 Y=255
    // inverted = 255 0 0), right half 50% black over white. Shown as red and mid grey.
    std::vector<std::uint8_t> cmyk(std::size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = &cmyk[(std::size_t(y) * w + x) * 4];
            if (x < w / 2) p[0] = 255, p[1] = 0, p[2] = 0, p[3] = 255;
            else p[0] = 255, p[1] = 255, p[2] = 255, p[3] = 128;
        }
    write_file(d / "c.jpg", encode_jpeg(cmyk, w, h, 4, JCS_CMYK, Scans::baseline));
    const Image c = read_image(d / "c.jpg");
    auto at = [&](int x, int y, int k) { return int(c.pixels[(std::size_t(y) * w + x) * 4 + k]); };
    EXPECT_NEAR(at(8, 16, 0), 255, 8);
    EXPECT_NEAR(at(8, 16, 1), 0, 8);
    EXPECT_NEAR(at(8, 16, 2), 0, 8);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(at(40, 16, k), 128, 8) << "channel " << k;
}

TEST(BadInputJpeg, TruncatedCorruptAndManyScanJpegsAreRefusedNamingTheFile) {
    TempDir d;
    int w = 0, h = 0;
    const std::vector<std::uint8_t> rgb = chelsea_rgb(w, h);
    const std::string whole = encode_jpeg(rgb, w, h, 3, JCS_RGB, Scans::baseline);
    auto refused = [&](const std::string& file, const std::string& why) {
        try {
            read_image(file);
            ADD_FAILURE() << file << " was decoded";
        } catch (const BadInput& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find(file), std::string::npos) << m;
            EXPECT_NE(m.find(why), std::string::npos) << m;
            std::printf("%s\n", m.c_str());
        }
    };
    // Half a file: libjpeg would fill the rest with grey and warn; ctmap refuses it.
    write_file(d / "half.jpg", whole.substr(0, whole.size() / 2));
    refused(d / "half.jpg", "truncated or corrupt");
    // The fuzz finding stb_image shifted by 32 bits on (UBSan): a corrupt entropy-coded stream.
    const std::string found = std::string(ctmap_test::source_dir()) +
                              "/fuzz/regressions/fuzz_image/stb-jpeg-bit-reader-underflow";
    const std::string copy = d / "found.jpg";
    write_file(copy, read_file(found));
    refused(copy, "JPEG");
    // 576 valid scans: a legal file, but past the 500 that libjpeg-turbo's TurboJPEG API allows too
    // (a crafted progressive file of many scans takes minutes).
    const std::string small(rgb.begin(), rgb.begin() + 32 * 32 * 3);
    write_file(d / "many.jpg",
               encode_jpeg(std::vector<std::uint8_t>(small.begin(), small.end()), 32, 32, 3, JCS_RGB, Scans::many));
    refused(d / "many.jpg", "more than 500 scans");
    // The same pixels in ten scans decode.
    write_file(d / "ten.jpg",
               encode_jpeg(std::vector<std::uint8_t>(small.begin(), small.end()), 32, 32, 3, JCS_RGB, Scans::progressive));
    EXPECT_EQ(read_image(d / "ten.jpg").width, 32);
}

}  // namespace
}  // namespace ctmap::test
