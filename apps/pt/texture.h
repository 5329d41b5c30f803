// texture.h - the scene's textures for the path tracer: pbrt-v4 "imagemap" (an image read through
// OpenImageIO, 8-bit files decoded from sRGB unless the texture says linear, repeated, bilinear or
// point-sampled at the finest level, t = 1 - v as pbrt-v4 looks images up) and "scale" (a texture times a factor). Float
// textures read an image's first channel, as pbrt-v4 does.
#pragma once

#include "scene.h"

#include <vector>

namespace udm1pt {

using udm1scene::Vec3;

class Textures {
public:
    // Reads every image once; a missing or unreadable one is a SceneError naming the file and the
    // Texture directive's file:line.
    explicit Textures(const udm1scene::Scene &scene);
    double value(int texture, double u, double v) const;  // float textures
    // spectrum textures, as albedos: clamped to [0, 1] (per channel: pbrt-v4 clamps an image's RGB, and
    // a scaled texture per wavelength, which is the same for grey values)
    Vec3 rgb(int texture, double u, double v) const;

private:
    struct Image {
        int width = 0, height = 0, channels = 0;
        std::vector<float> linear;  // row-major, top row first
    };
    Vec3 lookup(const Image &im, double u, double v, bool point) const;
    const std::vector<udm1scene::Texture> &tex_;
    std::vector<int> image_of_;  // per texture: its image, or -1 (scale)
    std::vector<Image> images_;
};

}  // namespace udm1pt
