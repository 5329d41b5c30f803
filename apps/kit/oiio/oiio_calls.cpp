// oiio_calls.cpp - the module libudm1_oiio.so (apps/kit/src/oiio_module.h): the kit's reading and writing of
// images through OpenImageIO, for the formats the kit does not read and write itself.
#include "../src/image_calls.h"
#include "../src/oiio_module.h"

#include "udm1app/cli.h"

#include <OpenImageIO/imageio.h>

#include <new>

namespace udm1app {

namespace {

int read_image_oiio(const std::string &path, LoadedImage &img, std::string &error)
{
    try {
        auto in = open_image(path);
        const OIIO::ImageSpec &spec = in->spec();
        img.width = spec.width;
        img.height = spec.height;
        img.channels = spec.nchannels;
        img.bits = (int)spec.format.size() * 8;
        for (const OIIO::ParamValue &pv : spec.extra_attribs)
            if (pv.name().string().rfind("udm1:", 0) == 0 && pv.type() == OIIO::TypeDesc::STRING)
                img.attributes[pv.name().string()] = pv.get_string();
        try {
            img.pixels.resize(image_values(*in, path));
        } catch (const std::bad_alloc &) {
            throw Error("cannot read '" + path + "': not enough memory for its " + std::to_string(img.width) + "x" +
                            std::to_string(img.height) + " pixels",
                        1);
        }
        read_pixels(*in, path, OIIO::TypeDesc::FLOAT, img.pixels.data());
        in->close();
        return 0;
    } catch (const Error &e) {
        error = e.what();
        return e.code;
    }
}

int write_image_oiio(AtomicFile &file, const std::vector<float> &pixels, int width, int height, int channels, bool srgb,
                     int bits, const std::vector<std::pair<std::string, std::string>> &attributes, std::string &error)
{
    try {
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
        return 0;
    } catch (const Error &e) {
        error = e.what();
        return e.code;
    }
}

const OiioCalls CALLS = {UDM1_OIIO_CALLS_VERSION, read_image_oiio, write_image_oiio};

}  // namespace

}  // namespace udm1app

extern "C" __attribute__((visibility("default"))) const udm1app::OiioCalls *udm1_app_oiio_calls()
{
    return &udm1app::CALLS;
}
