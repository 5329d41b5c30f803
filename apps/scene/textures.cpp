// textures.cpp - see textures.h.
#include "textures.h"

#include "pbrt_noise.h"

#include "udm1app/image_read.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

namespace udm1scene {

namespace {

const double PI = 3.14159265358979323846;

inline Vec3 clamp01(Vec3 c)
{
    return Vec3(std::clamp(c.x, 0.0, 1.0), std::clamp(c.y, 0.0, 1.0), std::clamp(c.z, 0.0, 1.0));
}

// floor(x) is odd (x finite; parity of the integer part without converting it to an integer type)
inline bool odd_floor(double x) { return std::fmod(std::fabs(std::floor(x)), 2.0) == 1.0; }

}  // namespace

Textures::Textures(const Scene &scene, const std::vector<int> &only) : tex_(scene.textures)
{
    std::vector<char> needed(tex_.size(), only.empty() ? 1 : 0);
    std::function<void(int)> need = [&](int i) {
        if (i < 0 || needed[i]) return;
        needed[i] = 1;
        for (const TextureInput *in : {&tex_[i].tex1, &tex_[i].tex2, &tex_[i].amount}) need(in->tex);
    };
    for (int i : only) need(i);
    std::map<std::pair<std::string, bool>, int> loaded;
    for (size_t k = 0; k < tex_.size(); ++k) {
        const Texture &t = tex_[k];
        wrap_.push_back(t.wrap == "clamp" ? Wrap::Clamp : t.wrap == "black" ? Wrap::Black : Wrap::Repeat);
        if (t.type != "imagemap" || !needed[k]) {
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
                throw SceneError(t.where + ": Texture \"" + t.name + "\": " + e.what());
            }
            if (li.width < 1 || li.height < 1 || li.channels < 1)
                throw SceneError(t.where + ": Texture \"" + t.name + "\": '" + t.filename + "' is empty");
            if (li.channels == 2)
                throw SceneError(t.where + ": Texture \"" + t.name + "\": '" + t.filename +
                                 "' has 2 channels (grey and alpha), which pbrt-v4 refuses (it needs R, G and B, or one channel)");
            Image im;
            im.width = li.width, im.height = li.height;
            im.channels = li.channels >= 3 ? 3 : 1;
            const size_t n = (size_t)im.width * im.height;
            if (li.channels >= 4)  // RGBA: the alpha counts where it is not 1 everywhere (pbrt-v4's MIPMap)
                for (size_t p = 0; p < n && im.channels == 3; ++p)
                    if (li.pixels[p * li.channels + 3] != 1.0f) im.channels = 4;
            im.linear.resize(n * im.channels);
            bool decode = t.srgb && li.bits <= 16;  // pbrt-v4 decodes integer files, every channel
            for (size_t p = 0; p < n; ++p)
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

double Textures::texel(const Image &im, long long x, long long y, int c, Wrap w) const
{
    auto wrap = [&](long long i, int n, bool *out) -> int {
        if (w == Wrap::Repeat) {
            long long k = i % n;
            return (int)(k < 0 ? k + n : k);
        }
        if (i < 0 || i >= n) {
            if (w == Wrap::Black) *out = true;
            return (int)std::clamp<long long>(i, 0, n - 1);
        }
        return (int)i;
    };
    bool out = false;
    int xi = wrap(x, im.width, &out), yi = wrap(y, im.height, &out);
    if (out) return 0;
    const float *p = &im.linear[((size_t)yi * im.width + xi) * im.channels];
    if (c >= 0) return p[c];
    return im.channels == 1 ? p[0] : (p[0] + p[1] + p[2]) / 3.0;  // (RGB, float: their average)
}

double Textures::bilerp(const Image &im, double s, double t, int c, Wrap w) const
{
    double x = s * im.width - 0.5, y = t * im.height - 0.5;
    if (!(std::fabs(x) < 9e18 && std::fabs(y) < 9e18)) return 0;  // (a non-finite or absurd coordinate)
    double fx = std::floor(x), fy = std::floor(y), dx = x - fx, dy = y - fy;
    long long x0 = (long long)fx, y0 = (long long)fy;
    return texel(im, x0, y0, c, w) * ((1 - dx) * (1 - dy)) + texel(im, x0 + 1, y0, c, w) * (dx * (1 - dy)) +
           texel(im, x0, y0 + 1, c, w) * ((1 - dx) * dy) + texel(im, x0 + 1, y0 + 1, c, w) * (dx * dy);
}

// At (s, 1 - t), as pbrt-v4 looks images up.
double Textures::lookup_float(int i, double s, double t) const
{
    const Image &im = images_[image_of_[i]];
    const Texture &tx = tex_[i];
    t = 1 - t;
    if (tx.point) {
        double x = std::round(s * im.width - 0.5), y = std::round(t * im.height - 0.5);
        if (!(std::fabs(x) < 9e18 && std::fabs(y) < 9e18)) return 0;
        return texel(im, (long long)x, (long long)y, 0, wrap_[i]);
    }
    int c = im.channels == 4 ? 3 : im.channels == 3 ? -1 : 0;
    return bilerp(im, s, t, c, wrap_[i]);
}

Vec3 Textures::lookup_rgb(int i, double s, double t) const
{
    const Image &im = images_[image_of_[i]];
    const Texture &tx = tex_[i];
    t = 1 - t;
    Vec3 c;
    for (int k = 0; k < 3; ++k) {
        int ch = im.channels == 1 ? 0 : k;
        if (tx.point) {
            double x = std::round(s * im.width - 0.5), y = std::round(t * im.height - 0.5);
            c[k] = std::fabs(x) < 9e18 && std::fabs(y) < 9e18 ? texel(im, (long long)x, (long long)y, ch, wrap_[i]) : 0;
        } else {
            c[k] = bilerp(im, s, t, ch, wrap_[i]);
        }
    }
    return c;
}

void Textures::map2d(const TextureMapping &m, const TexturePoint &at, double *s, double *t)
{
    if (m.kind == TextureMapping::UV) {
        *s = m.su * at.u + m.du, *t = m.sv * at.v + m.dv;
        return;
    }
    Vec3 p = m.texture_from_world.point(at.p);
    if (m.kind == TextureMapping::Spherical) {  // s = theta / pi, t = phi / 2 pi of the direction to p
        double len = length(p);
        Vec3 d = len > 0 ? p * (1 / len) : Vec3(0, 0, 1);
        double phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * PI;
        *s = std::acos(std::clamp(d.z, -1.0, 1.0)) / PI, *t = phi / (2 * PI);
    } else if (m.kind == TextureMapping::Cylindrical) {
        *s = (PI + std::atan2(p.y, p.x)) / (2 * PI), *t = p.z;
    } else {
        *s = m.du + dot(p, m.v1), *t = m.dv + dot(p, m.v2);
    }
}

// pbrt-v4's Checkerboard without a filter footprint: 0 where floor(s) + floor(t) (2D) or the floors of
// the point's coordinates (3D) add up to an even number, else 1.
double Textures::checkerboard(const Texture &t, const TexturePoint &at)
{
    bool odd;
    if (t.dimension == 2) {
        double s, tt;
        map2d(t.mapping, at, &s, &tt);
        odd = odd_floor(s) != odd_floor(tt);
    } else {
        Vec3 p = t.mapping.texture_from_world.point(at.p);
        odd = (odd_floor(p.x) != odd_floor(p.y)) != odd_floor(p.z);
    }
    return odd ? 1.0 : 0.0;
}

double Textures::input_value(const TextureInput &in, const TexturePoint &at) const
{
    return in.tex >= 0 ? value(in.tex, at) : in.value;
}

Vec3 Textures::input_rgb(const TextureInput &in, const TexturePoint &at) const
{
    return in.tex >= 0 ? raw_rgb(in.tex, at) : in.rgb;
}

double Textures::value(int i, const TexturePoint &at) const
{
    const Texture &t = tex_[i];
    if (t.type == "imagemap") {
        double s, tt;
        map2d(t.mapping, at, &s, &tt);
        double x = lookup_float(i, s, tt) * t.scale;
        return t.invert ? std::max(0.0, 1 - x) : x;
    }
    if (t.type == "constant") return t.tex1.value;
    if (t.type == "scale") {  // (pbrt-v4 skips the texture where the scale is 0)
        double sc = input_value(t.tex2, at);
        return sc == 0 ? 0 : input_value(t.tex1, at) * sc;
    }
    if (t.type == "fbm" || t.type == "wrinkled" || t.type == "windy") {
        Vec3 p = t.mapping.texture_from_world.point(at.p);
        return t.type == "fbm" ? pbrt_fbm(p, t.omega, t.octaves)
               : t.type == "wrinkled" ? pbrt_turbulence(p, t.omega, t.octaves) : pbrt_windy(p);
    }
    double a;
    if (t.type == "mix") a = input_value(t.amount, at);
    else if (t.type == "directionmix") a = 1 - std::fabs(dot(at.n, t.dir));  // (tex1 weighs |n . dir|)
    else a = checkerboard(t, at);
    double v1 = a != 1 ? input_value(t.tex1, at) : 0, v2 = a != 0 ? input_value(t.tex2, at) : 0;
    return (1 - a) * v1 + a * v2;
}

Vec3 Textures::raw_rgb(int i, const TexturePoint &at) const
{
    const Texture &t = tex_[i];
    if (t.type == "imagemap") {
        double s, tt;
        map2d(t.mapping, at, &s, &tt);
        Vec3 c = lookup_rgb(i, s, tt) * t.scale;
        if (t.invert) c = Vec3(1 - c.x, 1 - c.y, 1 - c.z);
        return clamp01(c);  // (pbrt-v4: an albedo image's RGB clamped to [0, 1])
    }
    if (t.type == "constant") return t.tex1.rgb;
    if (t.type == "scale") {
        double sc = input_value(t.tex2, at);
        return sc == 0 ? Vec3() : input_rgb(t.tex1, at) * sc;
    }
    double a;
    if (t.type == "mix") a = input_value(t.amount, at);
    else if (t.type == "directionmix") a = 1 - std::fabs(dot(at.n, t.dir));
    else a = checkerboard(t, at);
    Vec3 v1 = a != 1 ? input_rgb(t.tex1, at) : Vec3(), v2 = a != 0 ? input_rgb(t.tex2, at) : Vec3();
    return v1 * (1 - a) + v2 * a;
}

Vec3 Textures::rgb(int i, const TexturePoint &at) const { return clamp01(raw_rgb(i, at)); }

int Textures::add_normal_map(const std::string &filename, const std::string &where)
{
    udm1app::LoadedImage li;
    try {
        li = udm1app::read_image(filename);
    } catch (const std::exception &e) {
        throw SceneError(where + ": normalmap: " + e.what());
    }
    if (li.width < 1 || li.height < 1 || li.channels < 3)
        throw SceneError(where + ": normalmap: '" + filename + "' needs R, G and B channels (pbrt-v4's normal maps do)");
    Image im;
    im.width = li.width, im.height = li.height, im.channels = 3;
    im.linear.resize((size_t)im.width * im.height * 3);
    for (size_t p = 0; p < (size_t)im.width * im.height; ++p)
        for (int c = 0; c < 3; ++c) im.linear[3 * p + c] = li.pixels[p * li.channels + c];  // linear: as stored
    normal_maps_.push_back(std::move(im));
    return (int)normal_maps_.size() - 1;
}

Vec3 Textures::normal_map(int map, double u, double v) const
{
    const Image &im = normal_maps_[map];
    Vec3 n;
    for (int c = 0; c < 3; ++c) n[c] = 2 * bilerp(im, u, 1 - v, c, Wrap::Repeat) - 1;
    double len = length(n);
    return len > 0 ? n * (1 / len) : Vec3(0, 0, 1);
}

}  // namespace udm1scene
