// image_write.cpp - see image_write.h.
#include "udm1app/image_write.h"

#include "exr_file.h"
#include "oiio_module.h"
#include "png_write.h"
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace udm1app {

std::string image_extension(const std::string &path)
{
    const size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot + 1);
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return (char)std::tolower(c); });
    return e;
}

void write_image(AtomicFile &file, const std::vector<float> &pixels, int width, int height, int channels, bool srgb,
                 int bits, const std::vector<std::pair<std::string, std::string>> &attributes)
{
    const std::string &path = file.path(), ext = image_extension(path);
    // no time stamp: the same inputs give the same file, byte for byte, on every run
    std::vector<std::pair<std::string, std::string>> tags = {{"Software", "udm1"}};
    tags.insert(tags.end(), attributes.begin(), attributes.end());
    if (ext == "png") {
        std::vector<unsigned char> bytes = encode_png(pixels, width, height, channels, srgb, bits, tags, path);
        file.write(bytes.data(), bytes.size());
    } else if (ext == "exr") {
        if (channels < 1 || pixels.size() != (size_t)width * height * channels)
            throw Error("cannot write '" + path + "': the image has no pixels", 2);
        ExrImage exr;
        exr.full_width = exr.width = width, exr.full_height = exr.height = height;
        static const char *const NAMES[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < channels; ++c)
            exr.channels.push_back({channels == 1 ? "Y" : c < 4 ? NAMES[c] : "channel" + std::to_string(c), false});
        exr.pixels.resize(pixels.size());
        std::memcpy(exr.pixels.data(), pixels.data(), pixels.size() * sizeof(float));
        for (const auto &kv : tags) exr.attributes[kv.first] = kv.second;
        std::vector<unsigned char> bytes = encode_exr(exr, path);
        file.write(bytes.data(), bytes.size());
    } else {  // the other formats through OpenImageIO, loaded now
        std::string error;
        if (int code = oiio_calls("write", path).write_image(file, pixels, width, height, channels, srgb, bits, attributes, error))
            throw Error(error, code);
    }
}

void write_image(const std::string &path, const std::vector<float> &pixels, int width, int height, int channels,
                 bool srgb, int bits, const std::vector<std::pair<std::string, std::string>> &attributes)
{
    AtomicFile file(path);
    write_image(file, pixels, width, height, channels, srgb, bits, attributes);
    file.commit();
}

}  // namespace udm1app
