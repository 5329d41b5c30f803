// exr_file.h - OpenEXR files through the OpenEXR library itself: the tools' own outputs (images and images with
// exact sums) and the EXR files they read, without OpenImageIO (whose load with its dependencies costs a
// quarter of a second of processor time per program start: image_read.cpp and image_write.cpp load it only
// for the other formats).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace udm1app {

struct ExrChannel {
    std::string name;
    bool uint = false;  // a 32-bit unsigned channel, else float (a half channel is read as float)
};

struct ExrImage {
    int full_x0 = 0, full_y0 = 0, full_width = 0, full_height = 0;  // the display window (written from (0, 0))
    int x0 = 0, y0 = 0, width = 0, height = 0;  // the data window
    std::vector<ExrChannel> channels;  // in the caller's order (the file keeps them sorted by name)
    // per pixel of the data window, row-major, each channel's 4 bytes in `channels` order
    std::vector<uint32_t> pixels;
    std::map<std::string, std::string> attributes;  // string attributes
    int bits = 32;  // read: 16 where every colour channel in the file is half
    bool zip = true;  // written with zip-compressed scan lines, else uncompressed (larger, quicker to write and read)
};

// Whether the file begins as an OpenEXR file does (its magic number). Throws Error "cannot read 'path': ..." if it
// is not a regular file or cannot be opened.
bool is_exr_file(const std::string &path);

// The file's bytes: zip-compressed scan lines (uncompressed where image.zip is false), no time stamp. Throws Error naming `path` (used only for the
// message).
std::vector<unsigned char> encode_exr(const ExrImage &image, const std::string &path);

// Every channel of the file's (first part's) data window. The channels come in OpenImageIO's order: R, G, B, A
// where present, then the others in the file's order. Throws Error "cannot read 'path': ..." in one line.
ExrImage decode_exr(const std::string &path);

}  // namespace udm1app
