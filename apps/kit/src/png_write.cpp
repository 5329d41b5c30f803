// png_write.cpp - see png_write.h.
#include "png_write.h"

#include "udm1app/cli.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>

namespace udm1app {

namespace {

struct PngState {
    std::vector<unsigned char> *bytes;
    char message[256];
};

void on_write(png_structp png, png_bytep data, size_t n)
{
    auto *st = (PngState *)png_get_io_ptr(png);
    bool ok = true;
    try {
        st->bytes->insert(st->bytes->end(), data, data + n);
    } catch (const std::bad_alloc &) {
        ok = false;
    }
    if (!ok) png_error(png, "not enough memory");
}

void on_flush(png_structp) {}

void on_error(png_structp png, png_const_charp message)
{
    auto *st = (PngState *)png_get_error_ptr(png);
    std::snprintf(st->message, sizeof st->message, "%s", message);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

// The libpng calls, in a function that holds no C++ object (libpng's errors return here by longjmp, which
// would skip destructors). 1 on success, else 0 with st->message set.
int write_png(PngState *st, png_bytep *rows, int width, int height, int bits, int color, int srgb, png_textp text,
              int ntext)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, st, on_error, on_warning);
    if (!png) return 0;
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return 0;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return 0;
    }
    png_set_write_fn(png, st, on_write, on_flush);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, bits, color, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (srgb)
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    else
        png_set_gAMA(png, info, 1.0);
    if (ntext) png_set_text(png, info, text, ntext);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 1;
}

}  // namespace

std::vector<unsigned char> encode_png(const std::vector<float> &pixels, int width, int height, int channels, bool srgb,
                                      int bits, const std::vector<std::pair<std::string, std::string>> &attributes,
                                      const std::string &path)
{
    static const int COLOR[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA};
    if (channels < 1 || channels > 4 || width < 1 || height < 1 || (bits != 8 && bits != 16) ||
        pixels.size() != (size_t)width * height * channels)
        throw Error("cannot write '" + path + "': a PNG holds 1 to 4 channels of 8 or 16 bits", 2);
    const size_t row_bytes = (size_t)width * channels * (bits / 8);
    std::vector<unsigned char> data((size_t)height * row_bytes), bytes;
    const float top = bits == 8 ? 255.0f : 65535.0f;
    for (size_t i = 0; i < pixels.size(); ++i) {
        const float x = pixels[i];
        const unsigned v = std::isnan(x) ? 0u : (unsigned)(std::clamp(x, 0.0f, 1.0f) * top + 0.5f);
        if (bits == 8)
            data[i] = (unsigned char)v;
        else
            data[2 * i] = (unsigned char)(v >> 8), data[2 * i + 1] = (unsigned char)v;  // PNG is big-endian
    }
    std::vector<png_bytep> rows((size_t)height);
    for (int y = 0; y < height; ++y) rows[(size_t)y] = data.data() + (size_t)y * row_bytes;
    std::vector<png_text> text;
    for (const auto &kv : attributes) {
        png_text t{};
        t.compression = PNG_TEXT_COMPRESSION_NONE;
        t.key = const_cast<char *>(kv.first.c_str());
        t.text = const_cast<char *>(kv.second.c_str());
        t.text_length = kv.second.size();
        text.push_back(t);
    }
    PngState st{&bytes, "libpng could not start"};
    if (!write_png(&st, rows.data(), width, height, bits, COLOR[channels], srgb, text.data(), (int)text.size()))
        throw Error("cannot write '" + path + "': " + st.message, 1);
    return bytes;
}

}  // namespace udm1app
