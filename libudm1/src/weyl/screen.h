/* weyl/screen.h - progressive screen-space randomization of Weyl sequences (UDM1_RANDOMIZE_SCREEN with
 * desc.screen_spp = 0): pixel (x, y), stream (y << 32) | x, shifts dimension j by x G_j + y H_j (mod 2^64)
 * on top of the sequence's one random shift, and keeps its own points n = 0, 1, 2, ... of the sequence.
 *
 * Why it is blue at every sample count: a pixel's error is a sum over Fourier modes h of the integrand,
 * each weighted by how badly the first n points integrate it, |D_n(h.alpha)/n|^2 (large only where
 * h.alpha is close to an integer: the resonant modes). Shifting pixel (x, y) by x G + y H turns mode h
 * into the plane wave of screen frequency (h.G, h.H) mod 1. The generators (G, H) of each dimension pair
 * are chosen so that the modes that carry the error at n = 1 .. 256 land outside the low screen
 * frequencies: the construction and its argument are in docs/screen-space.md. Nothing here depends on n,
 * so every prefix of a pixel's samples keeps it; the pixel's own points are the sequence's, so its error
 * is that of a per-pixel random shift; the sequence's random shift keeps every pixel unbiased.
 * Like core/hash.h, every step here (the search included) is part of the ABI. */
#ifndef UDM1_WEYL_SCREEN_H
#define UDM1_WEYL_SCREEN_H

#include "seq/seq.h"

/* seq->screen_gen: 2 * dims words, G_j at 2 j and H_j at 2 j + 1, from the generators of seq->gen.
 * Returns OUT_OF_MEMORY (with its message) or OK. */
UDM1_HIDDEN udm1_status udm1_screen_generators(const char *fn, udm1_seq_t *seq);

/* The screen shift x G_j + y H_j of pixel stream (y << 32) | x in dimension dim (progressive mode). */
static inline uint64_t udm1_screen_pixel_shift(const udm1_seq_t *seq, uint64_t stream, uint32_t dim)
{
    return (stream & 0xFFFFFFFFull) * seq->screen_gen[2 * (size_t)dim] + (stream >> 32) * seq->screen_gen[2 * (size_t)dim + 1];
}

#endif /* UDM1_WEYL_SCREEN_H */
