// image_write.cpp - see image_write.h.
#include "udm1app/image_write.h"

#include "image_calls.h"
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"

#include <OpenImageIO/imageio.h>

namespace udm1app {

void write_image(AtomicFile &file, const std::vector<float> &pixels, int width, int height, int channels, bool srgb,
                 int bits, const std::vector<std::pair<std::string, std::string>> &attributes)
{
    const std::string &path = file.path();
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        OIIO::geterror();  // "could not find a format writer": said below, in one line
        throw Error("cannot write '" + path + "': no image format for its extension", 2);
    }
    OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT;
    std::string fmt = out->format_name();
    if (fmt == "png" || fmt == "jpeg" || fmt == "bmp" || fmt == "targa") type = OIIO::TypeDesc::UINT8;
    if (fmt == "png" && bits == 16) type = OIIO::TypeDesc::UINT16;
    if (fmt == "tiff") type = OIIO::TypeDesc::UINT16;
    OIIO::ImageSpec spec(width, height, channels, type);
    // no time stamp: the same inputs give the same file, byte for byte, on every run
    spec.attribute("DateTime", "");
    spec.attribute("Software", "udm1");
    for (const auto &kv : attributes) spec.attribute(kv.first, kv.second);
    if (fmt == "png") {
        spec.attribute("oiio:ColorSpace", srgb ? "sRGB" : "linear");
        if (!srgb) spec.attribute("oiio:Gamma", 1.0f);
    }
    encode_image(*out, spec, OIIO::TypeDesc::FLOAT, pixels.data(), file);
}

void write_image(const std::string &path, const std::vector<float> &pixels, int width, int height, int channels,
                 bool srgb, int bits, const std::vector<std::pair<std::string, std::string>> &attributes)
{
    AtomicFile file(path);
    write_image(file, pixels, width, height, channels, srgb, bits, attributes);
    file.commit();
}

}  // namespace udm1app
