// alpha.cpp - see alpha.h.
#include "alpha.h"

#include "surface.h"

#include <cstring>

namespace udm1scene {

uint64_t murmur_hash64a(const void *data, size_t n)
{
    const uint64_t m = 0xc6a4a7935bd1e995ull;
    const int r = 47;
    uint64_t h = n * m;  // (seed 0)
    const unsigned char *p = (const unsigned char *)data, *end = p + (n / 8) * 8;
    for (; p != end; p += 8) {
        uint64_t k;
        std::memcpy(&k, p, 8);
        k *= m;
        k ^= k >> r;
        k *= m;
        h ^= k;
        h *= m;
    }
    size_t rest = n & 7;
    if (rest) {
        for (size_t i = rest; i-- > 0;) h ^= (uint64_t)p[i] << (8 * i);
        h *= m;
    }
    h ^= h >> r;
    h *= m;
    h ^= h >> r;
    return h;
}

double ray_hash(const float o[3], const float d[3])
{
    float buf[6] = {o[0], o[1], o[2], d[0], d[1], d[2]};
    return (double)(uint32_t)murmur_hash64a(buf, sizeof buf) * 0x1p-32;
}

AlphaTest::AlphaTest(const Scene &scene)
{
    std::vector<int> used;
    for (const Shape &s : scene.shapes)
        if (s.alpha_tex >= 0) used.push_back(s.alpha_tex);
    if (!used.empty()) textures_ = std::make_unique<Textures>(scene, used);
}

double AlphaTest::alpha(const Shape &s, const Hit &h) const
{
    if (s.alpha_tex < 0) return s.alpha;
    return textures_->value(s.alpha_tex, texture_point(s, h));
}

}  // namespace udm1scene
