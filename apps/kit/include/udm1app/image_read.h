// image_read.h - reading an image's first channel through OpenImageIO, and the
// image comparison the renderers report (one definition everywhere).
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace udm1app {

struct LoadedImage {
    int width = 0, height = 0, channels = 0;
    int bits = 32;              // the file's bits per channel (8 for most PNGs)
    std::vector<float> pixels;  // all channels, row-major
    std::map<std::string, std::string> attributes;  // the string metadata whose names start with "udm1:"
};

// Throws Error naming the file if it cannot be read.
LoadedImage read_image(const std::string &path);

// An 8-bit file's sRGB-encoded value decoded to linear (pbrt-v4 decodes 8-bit images so).
inline float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Throws Error "cannot read 'path': not a regular file" for a device, FIFO or folder (a reader would wait on
// /dev/zero forever); a missing file is left to the reader's own error.
void require_regular_file(const std::string &path);

// MSE over every channel of every pixel, and PSNR = 10 log10(1 / MSE): the peak is 1 on linear
// values (AO lies in [0, 1]; radiance images are compared after clamping to [0, 1], see compare()).
struct Comparison {
    double mse = 0, rmse = 0, psnr = 0;
};
Comparison compare(const LoadedImage &a, const LoadedImage &reference, bool clamp01, std::vector<float> *abs_diff);

}  // namespace udm1app
