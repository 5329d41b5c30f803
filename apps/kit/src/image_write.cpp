// image_write.cpp - see image_write.h.
#include "udm1app/image_write.h"

#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"

#include <OpenImageIO/imageio.h>

namespace udm1app {

void write_image(const std::string &path, const std::vector<float> &pixels, int width, int height, int channels,
                 bool srgb, int bits, const std::vector<std::pair<std::string, std::string>> &attributes)
{
    AtomicFile file(path);
    auto out = OIIO::ImageOutput::create(file.temp_path());
    if (!out) throw Error("cannot write '" + path + "': no image format for its extension", 2);
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
    if (!out->open(file.temp_path(), spec) ||
        !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close())
        throw Error("cannot write '" + path + "': " + out->geterror(), 1);
    file.commit();
}

}  // namespace udm1app
