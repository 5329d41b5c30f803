// pixel_order.cpp - the stream and index of a pixel's sample (pixel_order.h).
#include "udm1app/pixel_order.h"

#include <udm1/domain.h>

#include <stdexcept>

namespace udm1app {

namespace {

uint64_t spread(uint64_t v)
{
    v &= 0xFFFFFFFFull;
    v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
    v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
    v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
}

// The 24 permutations of {0, 1, 2, 3}, in lexicographic order, as four 2-bit entries (entry d at bits 2d).
uint8_t permutation(uint32_t p, uint32_t d)
{
    static uint8_t table[24][4];
    static const bool filled = [] {
        int k = 0;
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
                for (int c = 0; c < 4; ++c)
                    for (int e = 0; e < 4; ++e)
                        if (a != b && a != c && a != e && b != c && b != e && c != e) {
                            table[k][0] = (uint8_t)a, table[k][1] = (uint8_t)b, table[k][2] = (uint8_t)c;
                            table[k][3] = (uint8_t)e, ++k;
                        }
        return true;
    }();
    (void)filled;
    return table[p][d];
}

}  // namespace

bool zorder_sampler(const std::string &sampler) { return sampler == "sobol" || sampler == "sobol-owen"; }

uint64_t PixelOrder::zorder_index(int x, int y, uint64_t n) const
{
    uint64_t m = ((spread((uint32_t)x) | (spread((uint32_t)y) << 1)) << log2_spp) | n;
    uint64_t out = 0;
    int low = (int)(bits & 1);  // a lone last bit when the bit count is odd
    for (int shift = (int)bits - 2; shift >= low; shift -= 2) {
        uint64_t higher = shift + 2 >= 64 ? 0 : m >> (shift + 2);
        uint32_t digit = (uint32_t)(m >> shift) & 3u;
        uint32_t p = (uint32_t)((udm1_mix64(higher ^ key ^ ((uint64_t)shift << 56)) >> 40) % 24);
        out |= (uint64_t)permutation(p, digit) << shift;
    }
    if (low) out |= (m & 1) ^ (udm1_mix64((m >> 1) ^ key ^ (0xB1ull << 56)) & 1);
    return out;
}

PixelOrder make_pixel_order(const std::string &sampler, uint32_t randomize, uint32_t spp, uint64_t seed, int width,
                            int height)
{
    PixelOrder order;
    if (randomize != UDM1_RANDOMIZE_SCREEN || !zorder_sampler(sampler)) return order;
    if (spp == 0 || (spp & (spp - 1)) != 0)
        throw std::runtime_error("--randomize screen with sampler '" + sampler +
                                 "' (Z-order) needs a power-of-two spp, not " + std::to_string(spp));
    uint32_t side = 0;
    while ((1ull << side) < (uint64_t)(width > height ? width : height)) ++side;
    while ((1u << order.log2_spp) < spp) ++order.log2_spp;
    order.zorder = true;
    order.bits = 2 * side + order.log2_spp;
    if (order.bits > 64)
        throw std::runtime_error("--randomize screen with sampler '" + sampler + "' (Z-order): " + std::to_string(spp) +
                                 " spp on a " + std::to_string(width) + "x" + std::to_string(height) +
                                 " image pass a 64-bit index");
    if (order.bits < 2) order.bits = 2;
    order.key = udm1_mix64(seed ^ 0x5A4F524445520000ull);  // "ZORDER"
    return order;
}

}  // namespace udm1app
