// image_write.h - writing images through OpenImageIO (PNG, EXR, TIFF, ...),
// atomically (no partial file on failure).
#pragma once

#include "udm1app/atomic_file.h"

#include <string>
#include <utility>
#include <vector>

namespace udm1app {

// Write a width x height image of `channels` floats per pixel (row-major, top
// row first) to `path`; the format comes from the extension: EXR float, PNG
// 8 or 16 bits (`bits`), TIFF 16 bits. Integer formats get the values clamped
// to [0, 1]; PNGs are tagged linear (a gAMA chunk of 1.0) unless `srgb`.
// `attributes` are stored as string metadata (EXR header, PNG text), e.g. what made the image.
// Throws Error naming the path on failure.
void write_image(const std::string &path, const std::vector<float> &pixels, int width, int height, int channels,
                 bool srgb = false, int bits = 8,
                 const std::vector<std::pair<std::string, std::string>> &attributes = {});

// The same image written into `file` (the format from the extension of file.path()), left for the caller
// to commit with the run's other outputs.
void write_image(AtomicFile &file, const std::vector<float> &pixels, int width, int height, int channels,
                 bool srgb = false, int bits = 8, const std::vector<std::pair<std::string, std::string>> &attributes = {});

// The extension of `path`'s file name in lower case, without the dot ("" if it has none): what picks the format.
std::string image_extension(const std::string &path);

}  // namespace udm1app
