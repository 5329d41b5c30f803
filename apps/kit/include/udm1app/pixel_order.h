// pixel_order.h - how a renderer names sample n of pixel (x, y) to the library: a stream and an index.
//
// Per pixel (every randomization but Z-order): stream (y << 32) | x, index n; the library's screen
// schemes for Weyl sequences work on these names.
// Z-order (--randomize screen with sobol or sobol-owen): one stream for the whole image and the index
// (Morton(x, y) * spp + n) with its base-4 digits permuted, each digit by one of the 24 permutations of
// {0, 1, 2, 3} that a hash of the digits above it selects (a lone last bit, for an odd log2 spp, XORed
// with a hash bit): the Z-order scheme of Ahmed and Wonka 2020 that pbrt-v4's ZSobol sampler uses, with
// one index for all dimensions (the sequence's own dimensions, Owen-scrambled once for the image). Blue
// at spp samples per pixel, which must be a power of two.
#pragma once

#include <cstdint>
#include <string>

namespace udm1app {

struct PixelOrder {
    bool zorder = false;
    uint32_t bits = 0;  // Z-order: the index's significant bits, 2 ceil(log2(max(width, height))) + log2 spp
    uint32_t log2_spp = 0;
    uint64_t key = 0;   // Z-order: the permutations' key, from the seed

    uint64_t stream(int x, int y) const { return zorder ? 0 : ((uint64_t)(uint32_t)y << 32) | (uint32_t)x; }
    uint64_t index(int x, int y, uint64_t n) const { return zorder ? zorder_index(x, y, n) : n; }
    uint64_t zorder_index(int x, int y, uint64_t n) const;
};

// The order of a render: Z-order for --randomize screen (udm1app::RANDOMIZE_SCREEN from parse_randomize)
// with sobol or sobol-owen, whose spp must then be a power of two (std::runtime_error otherwise); per
// pixel for everything else.
PixelOrder make_pixel_order(const std::string &sampler, uint32_t randomize, uint32_t spp, uint64_t seed, int width,
                            int height);

// Whether `sampler` takes the Z-order scheme under --randomize screen.
bool zorder_sampler(const std::string &sampler);

}  // namespace udm1app
