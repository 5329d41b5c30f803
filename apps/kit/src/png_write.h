// png_write.h - PNG files through libpng itself (the tools' PNG outputs, without loading OpenImageIO: see
// exr_file.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace udm1app {

// A width x height image of `channels` floats per pixel (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA; row-major, top
// row first) as the bytes of a PNG file of 8 or 16 bits per channel: values clamped to [0, 1] and rounded to the
// nearest step (NaN as 0); an sRGB chunk if `srgb`, else a gAMA chunk of 1.0 (linear values); `attributes` as
// text chunks. Throws Error naming `path` (used only for the message).
std::vector<unsigned char> encode_png(const std::vector<float> &pixels, int width, int height, int channels, bool srgb,
                                      int bits, const std::vector<std::pair<std::string, std::string>> &attributes,
                                      const std::string &path);

}  // namespace udm1app
