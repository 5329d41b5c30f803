// image_read.cpp - see image_read.h.
#include "udm1app/image_read.h"

#include "image_calls.h"
#include "udm1app/cli.h"

#include <OpenImageIO/imageio.h>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <new>

namespace udm1app {

void require_regular_file(const std::string &path)
{
    struct stat st;
    if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) throw Error("cannot read '" + path + "': not a regular file", 1);
}

LoadedImage read_image(const std::string &path)
{
    auto in = open_image(path);
    const OIIO::ImageSpec &spec = in->spec();
    LoadedImage img;
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
    return img;
}

Comparison compare(const LoadedImage &a, const LoadedImage &ref, bool clamp01, std::vector<float> *abs_diff)
{
    if (a.width != ref.width || a.height != ref.height)
        throw Error("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                        std::to_string(ref.width) + "x" + std::to_string(ref.height),
                    2);
    int ch = std::min(a.channels, ref.channels);
    if (ch > 3) ch = 3;  // colour only, no alpha
    double sum = 0;
    size_t n = (size_t)a.width * a.height;
    if (abs_diff) abs_diff->assign(n, 0.0f);
    for (size_t i = 0; i < n; ++i) {
        double d2 = 0;
        for (int c = 0; c < ch; ++c) {
            double x = a.pixels[i * a.channels + c], y = ref.pixels[i * ref.channels + c];
            if (clamp01) x = std::clamp(x, 0.0, 1.0), y = std::clamp(y, 0.0, 1.0);
            d2 += (x - y) * (x - y);
        }
        sum += d2;
        if (abs_diff) (*abs_diff)[i] = (float)std::sqrt(d2 / ch);
    }
    Comparison c;
    c.mse = sum / ((double)n * ch);
    c.rmse = std::sqrt(c.mse);
    c.psnr = c.mse > 0 ? 10.0 * std::log10(1.0 / c.mse) : INFINITY;
    return c;
}

}  // namespace udm1app
