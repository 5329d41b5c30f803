// alpha.h - pbrt-v4's alpha cut-outs ("float alpha", "texture alpha" on a shape): where a ray meets a
// shape whose alpha a is below 1, the hit counts only if a hash of the ray, u in [0, 1), is at most a
// (a <= 0: never; pbrt-v4's GeometricPrimitive::Intersect compares HashFloat(ray.o, ray.d) with a). Every
// primitive along one ray sees the same u, as in pbrt-v4; past a rejected hit on a quadric or a bilinear
// patch, the shape's own farther hit sees the hash of the ray continued from the rejected point (pbrt-v4
// traces that ray on, against the same shape). Shadow rays alike. The hash is of the ray's float origin
// and direction as traced (MurmurHash64A of their 24 bytes, its low 32 bits over 2^32, as pbrt-v4's
// HashFloat): deterministic, whatever the thread or the loop.
#pragma once

#include "embree_scene.h"
#include "scene.h"
#include "textures.h"

#include <memory>

namespace udm1scene {

// MurmurHash64A (Austin Appleby) of n bytes with seed 0.
uint64_t murmur_hash64a(const void *data, size_t n);
// pbrt-v4's HashFloat of a ray: u in [0, 1) from its float origin and direction.
double ray_hash(const float o[3], const float d[3]);

class AlphaTest {
public:
    // Reads the images of the shapes' alpha textures (SceneError naming the file and the Texture's line).
    explicit AlphaTest(const Scene &scene);
    // The alpha of shape s at hit h (h.p, h.ng, h.prim, h.u, h.v set).
    double alpha(const Shape &s, const Hit &h) const;
    // Whether the ray (o, d), as traced in float, meets shape s at h.
    bool passes(const Shape &s, const Hit &h, const float o[3], const float d[3]) const
    {
        double a = alpha(s, h);
        if (a >= 1) return true;
        return a > 0 && ray_hash(o, d) <= a;
    }

private:
    std::unique_ptr<Textures> textures_;
};

}  // namespace udm1scene
