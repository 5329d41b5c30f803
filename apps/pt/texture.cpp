// texture.cpp - see texture.h.
#include "texture.h"

#include "udm1app/image_read.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace udm1pt {

Textures::Textures(const udm1scene::Scene &scene) : tex_(scene.textures)
{
    std::map<std::pair<std::string, bool>, int> loaded;
    for (const udm1scene::Texture &t : tex_) {
        if (t.type != "imagemap") {
            image_of_.push_back(-1);
            continue;
        }
        auto key = std::make_pair(t.filename, t.srgb);
        auto it = loaded.find(key);
        if (it == loaded.end()) {
            udm1app::LoadedImage li;
            try {
                li = udm1app::read_image(t.filename);
            } catch (const std::exception &e) {
                throw udm1scene::SceneError(t.where + ": Texture \"" + t.name + "\": " + e.what());
            }
            if (li.width < 1 || li.height < 1 || li.channels < 1)
                throw udm1scene::SceneError(t.where + ": Texture \"" + t.name + "\": '" + t.filename + "' is empty");
            Image im;
            im.width = li.width, im.height = li.height, im.channels = std::min(li.channels, 3);
            im.linear.resize((size_t)im.width * im.height * im.channels);
            bool decode = t.srgb && li.bits == 8;  // pbrt-v4: the encoding applies to 8-bit files
            for (size_t p = 0; p < (size_t)im.width * im.height; ++p)
                for (int c = 0; c < im.channels; ++c) {
                    float x = li.pixels[p * li.channels + c];
                    im.linear[p * im.channels + c] = decode ? udm1app::srgb_to_linear(x) : x;
                }
            images_.push_back(std::move(im));
            it = loaded.emplace(key, (int)images_.size() - 1).first;
        }
        image_of_.push_back(it->second);
    }
}

// At the finest level with repeat wrapping, at (u, 1 - v): bilinear (pbrt-v4's Image::Bilerp), or the
// nearest texel (pbrt-v4's MIPMap point filter: the texel at round(s * width - 0.5)).
Vec3 Textures::lookup(const Image &im, double u, double v, bool point) const
{
    double x = u * im.width - 0.5, y = (1 - v) * im.height - 0.5;
    auto wrap = [](double i, int n) { long long k = (long long)i % n; return (int)(k < 0 ? k + n : k); };
    auto px = [&](int xi, int yi) {
        const float *p = &im.linear[((size_t)yi * im.width + xi) * im.channels];
        return im.channels >= 3 ? Vec3(p[0], p[1], p[2]) : Vec3(p[0], p[0], p[0]);
    };
    if (point) return px(wrap(std::round(x), im.width), wrap(std::round(y), im.height));
    double fx = std::floor(x), fy = std::floor(y), dx = x - fx, dy = y - fy;
    int x0 = wrap(fx, im.width), x1 = wrap(fx + 1, im.width), y0 = wrap(fy, im.height), y1 = wrap(fy + 1, im.height);
    return px(x0, y0) * ((1 - dx) * (1 - dy)) + px(x1, y0) * (dx * (1 - dy)) + px(x0, y1) * ((1 - dx) * dy) +
           px(x1, y1) * (dx * dy);
}

double Textures::value(int i, double u, double v) const
{
    const udm1scene::Texture &t = tex_[i];
    if (t.type == "scale") return t.scale * value(t.tex, u, v);
    double x = lookup(images_[image_of_[i]], u, v, t.point).x * t.scale;
    return t.invert ? std::max(0.0, 1 - x) : x;
}

Vec3 Textures::rgb(int i, double u, double v) const
{
    const udm1scene::Texture &t = tex_[i];
    if (t.type == "scale") {  // the albedo clamped to [0, 1] again after the factor, as pbrt-v4's materials clamp it
        Vec3 c = rgb(t.tex, u, v) * t.scale;
        return Vec3(std::clamp(c.x, 0.0, 1.0), std::clamp(c.y, 0.0, 1.0), std::clamp(c.z, 0.0, 1.0));
    }
    Vec3 c = lookup(images_[image_of_[i]], u, v, t.point) * t.scale;
    if (t.invert) c = Vec3(1 - c.x, 1 - c.y, 1 - c.z);
    return Vec3(std::clamp(c.x, 0.0, 1.0), std::clamp(c.y, 0.0, 1.0), std::clamp(c.z, 0.0, 1.0));
}

}  // namespace udm1pt
