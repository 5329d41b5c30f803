// image_read.cpp - see image_read.h.
#include "udm1app/image_read.h"

#include "exr_file.h"
#include "oiio_module.h"
#include "udm1app/cli.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace udm1app {

LoadedImage read_image(const std::string &path)
{
    LoadedImage img;
    if (!is_exr_file(path)) {  // the other formats through OpenImageIO, loaded now
        std::string error;
        if (int code = oiio_calls("read", path).read_image(path, img, error)) throw Error(error, code);
        return img;
    }
    ExrImage exr = decode_exr(path);
    img.width = exr.width, img.height = exr.height, img.channels = (int)exr.channels.size(), img.bits = exr.bits;
    for (const auto &kv : exr.attributes)
        if (kv.first.rfind("udm1:", 0) == 0) img.attributes[kv.first] = kv.second;
    img.pixels.resize(exr.pixels.size());
    for (size_t i = 0; i < exr.pixels.size(); ++i) {
        const uint32_t v = exr.pixels[i];
        if (exr.channels[i % exr.channels.size()].uint) {
            img.pixels[i] = (float)((double)v / 4294967295.0);  // as OpenImageIO converts them: 0 to 1
        } else {
            float f;
            std::memcpy(&f, &v, sizeof f);
            img.pixels[i] = f;
        }
    }
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
