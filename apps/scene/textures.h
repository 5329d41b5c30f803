// textures.h - the scene's textures (scene.h, Texture) evaluated as pbrt-v4 evaluates them, at the
// finest level of their images (udm1's renderers trace no ray differentials: pbrt-v4's footprint filters,
// and the checkerboard's box filter, see a point):
//   imagemap   an image read through OpenImageIO. Integer files (8 and 16 bits) are decoded from sRGB where
//              the texture's encoding is sRGB (pbrt-v4's default for .png files; linear for the others),
//              every channel, alpha too; float files are linear. Looked up at (s, 1 - t) of its mapping,
//              bilinear (pbrt-v4's Bilerp) or at the nearest texel ("filter" "point"), wrapped by "wrap"
//              (repeat, clamp, black). A float texture reads, bilinear, an RGB image's average, an RGBA
//              image's alpha (where it is not 1 everywhere), a one-channel image's value; point-sampled,
//              the first channel (pbrt-v4's MIPMap). A spectrum texture reads R, G, B (grey: the one
//              channel three times), clamped to [0, 1] as pbrt-v4 clamps an albedo image.
//   constant, scale, mix, directionmix, checkerboard, fbm, wrinkled, windy: scene.h.
// Spectrum textures are albedos (reflectance, transmittance, a medium's albedo): rgb() clamps the result to
// [0, 1] per channel, as pbrt-v4's materials clamp theirs.
#pragma once

#include "scene.h"

#include <vector>

namespace udm1scene {

// Where a texture is looked up: the world point, the unit geometric normal, the surface's (u, v).
struct TexturePoint {
    Vec3 p, n;
    double u = 0, v = 0;
};

class Textures {
public:
    // Reads the images of every texture, or (only non-empty) of those textures and what they use. A missing
    // or unreadable image, or one pbrt-v4 refuses (2 channels), is a SceneError naming the file and the
    // Texture directive's file:line.
    explicit Textures(const Scene &scene, const std::vector<int> &only = {});
    double value(int texture, const TexturePoint &at) const;  // float textures
    Vec3 rgb(int texture, const TexturePoint &at) const;     // spectrum textures, clamped to [0, 1]

    // (s, t) of a 2D mapping at a point.
    static void map2d(const TextureMapping &m, const TexturePoint &at, double *s, double *t);

    // A normal map (a material's "normalmap", pbrt-v4's NormalMap): an RGB image read linear (no sRGB
    // decoding), repeated; normal_map() looks it up bilinear at (u, 1 - v) and returns 2 rgb - 1 normalized
    // (the normal in the shading frame: x along dp/du, z the shading normal).
    int add_normal_map(const std::string &filename, const std::string &where);
    Vec3 normal_map(int map, double u, double v) const;

private:
    struct Image {
        int width = 0, height = 0, channels = 0;  // 1, 3 or 4 (RGBA whose alpha is not 1 everywhere)
        std::vector<float> linear;                // row-major, top row first
    };
    enum class Wrap { Repeat, Clamp, Black };
    // channel c (0..channels-1), or (c = -1) the channels' average, of texel (x, y) after wrapping
    double texel(const Image &im, long long x, long long y, int c, Wrap w) const;
    double bilerp(const Image &im, double s, double t, int c, Wrap w) const;
    double lookup_float(int i, double s, double t) const;
    Vec3 lookup_rgb(int i, double s, double t) const;
    double input_value(const TextureInput &in, const TexturePoint &at) const;
    Vec3 input_rgb(const TextureInput &in, const TexturePoint &at) const;
    Vec3 raw_rgb(int i, const TexturePoint &at) const;  // before the final clamp
    static double checkerboard(const Texture &t, const TexturePoint &at);  // 0: tex1, 1: tex2

    const std::vector<Texture> &tex_;
    std::vector<int> image_of_;  // per texture: its image, or -1
    std::vector<Wrap> wrap_;     // per texture
    std::vector<Image> images_;
    std::vector<Image> normal_maps_;
};

}  // namespace udm1scene
