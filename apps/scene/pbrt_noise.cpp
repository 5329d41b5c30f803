// pbrt_noise.cpp - pbrt-v4's solid noise and its octave sums (pbrt_noise.h).
#include "pbrt_noise.h"

#include "udm1/noise.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace udm1scene {

namespace {

// Ken Perlin's permutation, from the library's "perlin" noise table, twice over (so that perm[perm[x] + y]
// needs no wrap for x, y up to 256).
const std::array<int, 512> &permutation()
{
    static const std::array<int, 512> table = [] {
        udm1_noise_desc desc;
        udm1_noise_desc_init(&desc);
        udm1_noise *noise = nullptr;
        uint8_t perm[256];
        double gradients[768];
        if (udm1_noise_create(&desc, &noise) != UDM1_OK || udm1_noise_tables(noise, perm, gradients) != UDM1_OK) {
            udm1_noise_destroy(noise);
            throw std::runtime_error(std::string("udm1: noise table: ") + udm1_last_error());
        }
        udm1_noise_destroy(noise);
        std::array<int, 512> t{};
        for (int i = 0; i < 512; ++i) t[i] = perm[i & 255];
        return t;
    }();
    return table;
}

// The corner's hash picks one of 12 edge directions (four twice), pbrt-v4's way.
double gradient(const std::array<int, 512> &perm, int x, int y, int z, double dx, double dy, double dz)
{
    int h = perm[perm[perm[x] + y] + z] & 15;
    double u = h < 8 || h == 12 || h == 13 ? dx : dy;
    double v = h < 4 || h == 12 || h == 13 ? dy : dz;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

double lerp(double t, double a, double b) { return (1 - t) * a + t * b; }

}  // namespace

double pbrt_noise(Vec3 p)
{
    const std::array<int, 512> &perm = permutation();
    // (coordinates reduced modulo 2^30 first, as pbrt-v4 does, so that the cell index fits an int)
    const double wrap = 1 << 30;
    double x = std::fmod(p.x, wrap), y = std::fmod(p.y, wrap), z = std::fmod(p.z, wrap);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return 0;
    double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    double dx = x - fx, dy = y - fy, dz = z - fz;
    int ix = (int)fx & 255, iy = (int)fy & 255, iz = (int)fz & 255;
    double w000 = gradient(perm, ix, iy, iz, dx, dy, dz), w100 = gradient(perm, ix + 1, iy, iz, dx - 1, dy, dz);
    double w010 = gradient(perm, ix, iy + 1, iz, dx, dy - 1, dz), w110 = gradient(perm, ix + 1, iy + 1, iz, dx - 1, dy - 1, dz);
    double w001 = gradient(perm, ix, iy, iz + 1, dx, dy, dz - 1), w101 = gradient(perm, ix + 1, iy, iz + 1, dx - 1, dy, dz - 1);
    double w011 = gradient(perm, ix, iy + 1, iz + 1, dx, dy - 1, dz - 1);
    double w111 = gradient(perm, ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1);
    double wx = fade(dx), wy = fade(dy), wz = fade(dz);
    double y0 = lerp(wy, lerp(wx, w000, w100), lerp(wx, w010, w110));
    double y1 = lerp(wy, lerp(wx, w001, w101), lerp(wx, w011, w111));
    return lerp(wz, y0, y1);
}

double pbrt_fbm(Vec3 p, double omega, int octaves)
{
    double sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += o * pbrt_noise(p * lambda);
        lambda *= 1.99, o *= omega;
    }
    return sum;
}

double pbrt_turbulence(Vec3 p, double omega, int octaves)
{
    double sum = 0, lambda = 1, o = 1;
    for (int i = 0; i < octaves; ++i) {
        sum += o * std::fabs(pbrt_noise(p * lambda));
        lambda *= 1.99, o *= omega;
    }
    return sum + o * 0.2;  // (pbrt-v4's term for the octave past the last, at a footprint of 0)
}

double pbrt_windy(Vec3 p) { return std::fabs(pbrt_fbm(p * 0.1, 0.5, 3)) * pbrt_fbm(p, 0.5, 6); }

}  // namespace udm1scene
