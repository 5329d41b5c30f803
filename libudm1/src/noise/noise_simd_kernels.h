/* noise_simd_kernels.h - the blocked batch kernels of noise_simd.c, included
 * once per instruction set with KERNEL_ATTR (the target attribute), NOISE3,
 * NOISE2 (the functions' names), GRAD3 and GRAD2 (that set's gradients)
 * defined. Not a public header. Each kernel returns how many leading points
 * it computed: all of them in groups of four, or up to the first group with a
 * non-finite coordinate, which the caller then finds and reports; and checks
 * the coordinates of `side` beside them, a step per block (noise/side_check.h). */

/* Points go in blocks of BLOCK groups of four, in passes: the cells and their column hashes
 * (hash4) of every group, then the corner hashes (pair), then the gradients and lerps. Each
 * pass is a short loop whose loads do not depend on each other across groups, so the
 * processor overlaps their cache misses (the tables are 256 KiB); one long loop per group
 * stalled on them (perf: a third of the time on the two dependent loads). */
KERNEL_ATTR static size_t NOISE3(const udm1_noise *n, const double *xyz, size_t count, size_t stride, double *out,
                                 udm1_side_check *side)
{
    size_t i = 0;
    int stop = 0;
    __m256d checked = _mm256_setzero_pd();
    while (i + 4 <= count && !stop) {
        checked = udm1_side_step256_pd(side, checked);
        size_t groups = (count - i) / 4 < BLOCK ? (count - i) / 4 : BLOCK;
        __m256d fx[BLOCK], fy[BLOCK], fz[BLOCK];
        __m128i z0[BLOCK];
        int32_t ci[BLOCK * 4], qi[BLOCK * 16];
        uint32_t c4[BLOCK * 4];
        int32_t q[BLOCK * 16]; /* per group: the pair words of columns A, B, A1, B1, four lanes each */
        unsigned scalar = 0;   /* groups with a coordinate at or past 2^31: the scalar code */
        for (size_t g = 0; g < groups; ++g) {
            const double *p = xyz + (i + 4 * g) * stride;
            __builtin_prefetch((const void *)((uintptr_t)p + PREFETCH * stride * sizeof(double)), 0, 0);
            __m256d x = _mm256_set_pd(p[3 * stride], p[2 * stride], p[stride], p[0]);
            __m256d y = _mm256_set_pd(p[3 * stride + 1], p[2 * stride + 1], p[stride + 1], p[1]);
            __m256d z = _mm256_set_pd(p[3 * stride + 2], p[2 * stride + 2], p[stride + 2], p[2]);
            if (!(in_range(x) && in_range(y) && in_range(z))) {
                if (!(all_finite(x) && all_finite(y) && all_finite(z))) { /* stop before it: the caller reports it */
                    groups = g;
                    stop = 1;
                    break;
                }
                scalar |= 1u << g;
                x = y = z = _mm256_setzero_pd();
            }
            __m128i X0, X1, Y0, Y1, Z1;
            fx[g] = axis(x, &X0, &X1);
            fy[g] = axis(y, &Y0, &Y1);
            fz[g] = axis(z, &z0[g], &Z1);
            _mm_storeu_si128((__m128i *)(ci + 4 * g), _mm_or_si128(_mm_slli_epi32(X0, 8), Y0));
        }
        /* the four column hashes perm[perm[x] + y] of each cell in one load (hash4) */
        for (size_t k = 0; k < 4 * groups; ++k) c4[k] = n->hash4[ci[k]];
        __m128i m = _mm_set1_epi32(255);
        for (size_t g = 0; g < groups; ++g) { /* each column's hashes at z and z + 1 in one load (pair) */
            __m128i c = _mm_loadu_si128((const __m128i *)(c4 + 4 * g)), Z0 = z0[g];
            _mm_storeu_si128((__m128i *)(qi + 16 * g), _mm_add_epi32(_mm_and_si128(c, m), Z0));
            _mm_storeu_si128((__m128i *)(qi + 16 * g + 4), _mm_add_epi32(_mm_and_si128(_mm_srli_epi32(c, 16), m), Z0));
            _mm_storeu_si128((__m128i *)(qi + 16 * g + 8), _mm_add_epi32(_mm_and_si128(_mm_srli_epi32(c, 8), m), Z0));
            _mm_storeu_si128((__m128i *)(qi + 16 * g + 12), _mm_add_epi32(_mm_srli_epi32(c, 24), Z0));
        }
        for (size_t k = 0; k < 16 * groups; ++k) q[k] = n->pair[qi[k]];
        for (size_t g = 0; g < groups; ++g, i += 4) {
            if (scalar >> g & 1u) {
                for (size_t k = 0; k < 4; ++k) {
                    const double *p = xyz + (i + k) * stride;
                    out[i + k] = udm1_noise_3d(n, p[0], p[1], p[2]);
                }
                continue;
            }
            __m256d x = fx[g], y = fy[g], z = fz[g];
            __m256d u = fade(x), v = fade(y), w = fade(z);
            __m256d one = _mm256_set1_pd(1.0), x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one),
                    z1 = _mm256_sub_pd(z, one);
            const __m128i *qg = (const __m128i *)(q + 16 * g);
            __m128i qA = _mm_loadu_si128(qg), qB = _mm_loadu_si128(qg + 1), qA1 = _mm_loadu_si128(qg + 2),
                    qB1 = _mm_loadu_si128(qg + 3);
            __m256d g000 = GRAD3(qA, x, y, z);
            __m256d g100 = GRAD3(qB, x1, y, z);
            __m256d g010 = GRAD3(qA1, x, y1, z);
            __m256d g110 = GRAD3(qB1, x1, y1, z);
            __m256d g001 = GRAD3(_mm_srli_epi32(qA, 8), x, y, z1);
            __m256d g101 = GRAD3(_mm_srli_epi32(qB, 8), x1, y, z1);
            __m256d g011 = GRAD3(_mm_srli_epi32(qA1, 8), x, y1, z1);
            __m256d g111 = GRAD3(_mm_srli_epi32(qB1, 8), x1, y1, z1);
            __m256d r = lerp(w, lerp(v, lerp(u, g000, g100), lerp(u, g010, g110)),
                             lerp(v, lerp(u, g001, g101), lerp(u, g011, g111)));
            _mm256_storeu_pd(out + i, r);
        }
    }
    udm1_side_end256_pd(side, checked);
    return i;
}

KERNEL_ATTR static size_t NOISE2(const udm1_noise *n, const double *xyz, size_t count, size_t stride, double *out,
                                 udm1_side_check *side)
{
    size_t i = 0;
    int stop = 0;
    __m256d checked = _mm256_setzero_pd();
    while (i + 4 <= count && !stop) {
        checked = udm1_side_step256_pd(side, checked);
        size_t groups = (count - i) / 4 < BLOCK ? (count - i) / 4 : BLOCK;
        __m256d fx[BLOCK], fy[BLOCK];
        int32_t ci[BLOCK * 4];
        uint32_t c4[BLOCK * 4];
        unsigned scalar = 0;
        for (size_t g = 0; g < groups; ++g) {
            const double *p = xyz + (i + 4 * g) * stride;
            __builtin_prefetch((const void *)((uintptr_t)p + PREFETCH * stride * sizeof(double)), 0, 0);
            __m256d x = _mm256_set_pd(p[3 * stride], p[2 * stride], p[stride], p[0]);
            __m256d y = _mm256_set_pd(p[3 * stride + 1], p[2 * stride + 1], p[stride + 1], p[1]);
            if (!(in_range(x) && in_range(y))) {
                if (!(all_finite(x) && all_finite(y))) {
                    groups = g;
                    stop = 1;
                    break;
                }
                scalar |= 1u << g;
                x = y = _mm256_setzero_pd();
            }
            __m128i X0, X1, Y0, Y1;
            fx[g] = axis(x, &X0, &X1);
            fy[g] = axis(y, &Y0, &Y1);
            _mm_storeu_si128((__m128i *)(ci + 4 * g), _mm_or_si128(_mm_slli_epi32(X0, 8), Y0));
        }
        /* the cell's four corner hashes perm[perm[x] + y] in one load (hash4) */
        for (size_t k = 0; k < 4 * groups; ++k) c4[k] = n->hash4[ci[k]];
        for (size_t g = 0; g < groups; ++g, i += 4) {
            if (scalar >> g & 1u) {
                for (size_t k = 0; k < 4; ++k) {
                    const double *p = xyz + (i + k) * stride;
                    out[i + k] = udm1_noise_2d(n, p[0], p[1]);
                }
                continue;
            }
            __m256d x = fx[g], y = fy[g];
            __m256d u = fade(x), v = fade(y);
            __m256d one = _mm256_set1_pd(1.0), x1 = _mm256_sub_pd(x, one), y1 = _mm256_sub_pd(y, one);
            __m128i c = _mm_loadu_si128((const __m128i *)(c4 + 4 * g));
            __m256d g00 = GRAD2(c, x, y);
            __m256d g10 = GRAD2(_mm_srli_epi32(c, 16), x1, y);
            __m256d g01 = GRAD2(_mm_srli_epi32(c, 8), x, y1);
            __m256d g11 = GRAD2(_mm_srli_epi32(c, 24), x1, y1);
            __m256d r = lerp(v, lerp(u, g00, g10), lerp(u, g01, g11));
            _mm256_storeu_pd(out + i, _mm256_mul_pd(_mm256_set1_pd(0.507), r)); /* noise1234's scale */
        }
    }
    udm1_side_end256_pd(side, checked);
    return i;
}
