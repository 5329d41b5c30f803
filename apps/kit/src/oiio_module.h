// oiio_module.h - OpenImageIO, loaded when a tool first needs it: to read an image that is not OpenEXR (a
// texture, a PNG reference) or to write a format other than OpenEXR and PNG. Debian's OpenImageIO with its
// dependencies (OpenCV, GDAL, FFmpeg, about 260 libraries bound at load) costs a quarter of a second of
// processor time per program start; most runs read and write only OpenEXR and PNG (exr_file.h, png_write.h).
// The module (libudm1_oiio.so, built beside the tools: apps/kit/oiio/) holds the kit's OpenImageIO calls.
#pragma once

#include "udm1app/atomic_file.h"
#include "udm1app/image_read.h"

#include <string>
#include <utility>
#include <vector>

namespace udm1app {

// The module's calls: 0 on success, else the tool's exit code with `error` set to the one-line message.
struct OiioCalls {
    int version;  // UDM1_OIIO_CALLS_VERSION
    int (*read_image)(const std::string &path, LoadedImage &out, std::string &error);
    int (*write_image)(AtomicFile &file, const std::vector<float> &pixels, int width, int height, int channels,
                       bool srgb, int bits, const std::vector<std::pair<std::string, std::string>> &attributes,
                       std::string &error);
};

#define UDM1_OIIO_CALLS_VERSION 1

// The module's calls, loaded on the first call (thread-safe); throws Error "cannot <verb> '<path>': ..." naming
// the module where it cannot be loaded.
const OiioCalls &oiio_calls(const char *verb, const std::string &path);

}  // namespace udm1app
