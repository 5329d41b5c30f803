/* sobol.c - the Sobol sequence with Joe and Kuo's direction numbers
 * (new-joe-kuo-6.21201), 64 bits.
 *
 * The table of primitive polynomials and initial numbers m_1..m_s is generated
 * at build time (libudm1/gen/sobol_table.py, from scipy's copy or Joe and Kuo's
 * file); it is not kept in the source tree. Direction numbers:
 *   V_k = m_k 2^(64-k)                                    k = 1..s
 *   V_k = V_{k-s} ^ (V_{k-s} >> s) ^ XOR_i a_i V_{k-i}    k > s
 * with a_i the inner coefficients of the polynomial. Dimension 0 is the van der
 * Corput sequence. Point n is the XOR of V_k over the set bits of the Gray code
 * n ^ (n >> 1): the order of scipy.stats.qmc.Sobol, whose doubles with
 * bits=53 and scramble=False equal ours with UDM1_RANDOMIZE_NONE.
 */
#include "core/bits.h"
#include "samplers/samplers.h"
#include "seq/scramble.h"

#include <stdlib.h>
#include <string.h>

#if defined(UDM1_HAVE_SOBOL_TABLE)
extern const uint32_t udm1_sobol_table_dims;
extern const uint32_t udm1_sobol_table_poly[];
extern const uint32_t udm1_sobol_table_offset[];
extern const uint32_t udm1_sobol_table_m[];
#endif

/* dims x 64 direction numbers; for the first TABLE_DIMS dimensions also the XOR of every subset of the
 * first 8, indexed by the subset's bits (the Gray code's low byte), so that a point of up to 256
 * samples is one load a dimension: a loop over the set bits mispredicts its exit about once a
 * dimension, which cost more than the rest of the value; for the first BYTE_DIMS the subsets of each byte of
 * the first 32 numbers too (12 KiB a dimension with their reversed tops), which udm1_stream's inline draws
 * read: a stream whose dimensions end by BYTE_DIMS draws inline (OpenQMC's protocol draws 256) */
enum { TABLE_DIMS = 256, BYTE_DIMS = 256 };
typedef struct sobol {
    uint32_t table_dims, byte_dims;
    uint64_t (*low)[256];
    uint64_t (*bytes)[4][256]; /* the first BYTE_DIMS dimensions: the subsets of direction numbers 0..31, by byte */
    uint32_t (*rev)[4][256];   /* the bit reversal of their top 32 bits (udm1_stream's Owen-scrambled draws) */
    uint64_t v[][64];
} sobol;

/* The first 32 bits of the Gray code g of dimension dim (< byte_dims): four loads, no branch. Random
 * indices (a domain's permuted ones) have about twelve set bits above the low byte. */
static inline uint64_t sobol_bytes(const sobol *t, uint32_t dim, uint64_t g)
{
    uint64_t(*b)[256] = t->bytes[dim];
    return b[0][g & 255u] ^ b[1][(g >> 8) & 255u] ^ b[2][(g >> 16) & 255u] ^ b[3][(g >> 24) & 255u];
}

static uint64_t sobol_raw(const sobol *t, uint32_t dim, uint64_t n)
{
    uint64_t g = n ^ (n >> 1), x = 0;
    const uint64_t *v = t->v[dim];
    if (dim < t->byte_dims) {
        x = sobol_bytes(t, dim, g);
        g &= ~(uint64_t)0xFFFFFFFFu;
    } else if (dim < t->table_dims) {
        x = t->low[dim][g & 255u];
        g &= ~(uint64_t)255u;
    }
    for (; g; g &= g - 1) x ^= v[udm1_ctz64(g)]; /* one step per (remaining) set bit */
    return x;
}

static uint64_t sobol_base2(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    (void)skey;
    return sobol_raw(seq->data, dim, index) + seq->offset[dim];
}

/* sobol_raw of dimensions dim0 .. dim0 + m - 1 at once: where every one has its low-byte table, the
 * Gray code's higher set bits found once and each XORed into every dimension (the branch on the bits
 * taken once, not once a dimension) */
static void sobol_raw_dims(const sobol *t, uint64_t n, uint32_t dim0, uint32_t m, uint64_t *raw)
{
    uint64_t g = n ^ (n >> 1);
    if (dim0 + m <= t->byte_dims) {
        for (uint32_t k = 0; k < m; ++k) raw[k] = sobol_bytes(t, dim0 + k, g);
        for (uint64_t b = g & ~(uint64_t)0xFFFFFFFFu; b; b &= b - 1) {
            unsigned bit = (unsigned)udm1_ctz64(b);
            for (uint32_t k = 0; k < m; ++k) raw[k] ^= t->v[dim0 + k][bit];
        }
        return;
    }
    if (dim0 + m <= t->table_dims) {
        for (uint32_t k = 0; k < m; ++k) raw[k] = t->low[dim0 + k][g & 255u];
        for (uint64_t b = g & ~(uint64_t)255u; b; b &= b - 1) {
            unsigned bit = (unsigned)udm1_ctz64(b);
            for (uint32_t k = 0; k < m; ++k) raw[k] ^= t->v[dim0 + k][bit];
        }
        return;
    }
    for (uint32_t j = 0; j < m; ++j) raw[j] = sobol_raw(t, dim0 + j, n);
}

static void sobol_base2_point(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim0, uint32_t m,
                              uint64_t *raw)
{
    (void)skey;
    sobol_raw_dims(seq->data, index, dim0, m, raw);
    for (uint32_t j = 0; j < m; ++j) raw[j] += seq->offset[dim0 + j];
}

static uint64_t sobol_value(const udm1_seq_t *seq, uint64_t skey, uint64_t index, uint32_t dim)
{
    return udm1_randomize_base2(seq->mode, sobol_base2(seq, skey, index, dim), udm1_word(seq, skey, dim));
}

/* Sequential fill: the Gray code changes one bit per step. Owen scrambling comes after, over many values
 * at once (udm1_owen64_many: the same values as one udm1_owen64 each, four lanes at a time). */
static void sobol_fill(const udm1_seq_t *seq, uint64_t skey, uint64_t first, size_t count, uint32_t dim0,
                       uint32_t nd, uint64_t *raw)
{
    const sobol *t = seq->data;
    const int owen = seq->mode == UDM1_MODE_OWEN;
    uint64_t x0[64]; /* the first point's raw values, 64 dimensions at a time */
    for (uint32_t j = 0; j < nd; ++j) {
        uint32_t dim = dim0 + j;
        if (j % 64 == 0) sobol_raw_dims(t, first, dim, nd - j < 64 ? nd - j : 64, x0);
        uint64_t x = x0[j % 64], r = udm1_word(seq, skey, dim), o = seq->offset[dim];
        const uint64_t *v = t->v[dim];
        for (size_t i = 0; i < count; ++i) {
            raw[i * nd + j] = owen ? x + o : udm1_randomize_base2(seq->mode, x + o, r);
            uint64_t next = first + i + 1; /* Gray(next) = Gray(next - 1) ^ 2^ctz(next) */
            if (next) x ^= v[udm1_ctz64(next)];
        }
    }
    if (!owen || !nd || !count) return;
    enum { BLOCK = 512 };
    uint64_t words[BLOCK]; /* the dimensions' words, repeated row after row */
    if (nd > BLOCK) {
        for (size_t i = 0; i < count; ++i)
            for (uint32_t j0 = 0; j0 < nd; j0 += BLOCK) {
                uint32_t m = nd - j0 < BLOCK ? nd - j0 : BLOCK;
                for (uint32_t j = 0; j < m; ++j) words[j] = udm1_word(seq, skey, dim0 + j0 + j);
                udm1_owen64_many(raw + i * nd + j0, words, raw + i * nd + j0, m, 1);
            }
        return;
    }
    size_t rows = BLOCK / nd < count ? BLOCK / nd : count; /* the words of the rows a call has, no more */
    for (uint32_t j = 0; j < nd; ++j) words[j] = udm1_word(seq, skey, dim0 + j);
    for (size_t have = nd; have < rows * nd; have *= 2) /* the first row repeated, by doubling the copy */
        memcpy(words + have, words, (have < rows * nd - have ? have : rows * nd - have) * sizeof *words);
    for (size_t i = 0; i < count; i += rows) {
        size_t m = count - i < rows ? count - i : rows;
        udm1_owen64_many(raw + i * nd, words, raw + i * nd, (uint32_t)(m * nd), 1);
    }
}

udm1_status udm1_init_sobol(udm1_seq_t *seq)
{
#if defined(UDM1_HAVE_SOBOL_TABLE)
    if (seq->dims > udm1_sobol_table_dims)
        return udm1_fail(UDM1_ERROR_DIMENSION, "udm1_seq_create: the Sobol table has %u dimensions, %u asked",
                         udm1_sobol_table_dims, seq->dims);
    uint32_t td = seq->dims < TABLE_DIMS ? seq->dims : TABLE_DIMS, bd = seq->dims < BYTE_DIMS ? seq->dims : BYTE_DIMS;
    size_t head = sizeof(sobol) + sizeof(uint64_t) * 64 * seq->dims;
    head = (head + 63) / 64 * 64;
    sobol *t = malloc(head + sizeof(uint64_t) * 256 * (td + 4 * (size_t)bd) + sizeof(uint32_t) * 256 * 4 * (size_t)bd);
    if (!t) return udm1_fail(UDM1_ERROR_OUT_OF_MEMORY, "udm1_seq_create: out of memory for %u dimensions", seq->dims);
    t->table_dims = td;
    t->byte_dims = bd;
    t->low = (uint64_t(*)[256])((char *)t + head);
    t->bytes = (uint64_t(*)[4][256])((char *)t + head + sizeof(uint64_t) * 256 * td);
    t->rev = (uint32_t(*)[4][256])((char *)t->bytes + sizeof(uint64_t) * 256 * 4 * (size_t)bd);
    for (uint32_t j = 0; j < seq->dims; ++j) {
        uint64_t *v = t->v[j];
        uint32_t poly = udm1_sobol_table_poly[j];
        uint32_t s = 0;
        while ((poly >> (s + 1)) != 0) ++s; /* degree */
        const uint32_t *m = udm1_sobol_table_m + udm1_sobol_table_offset[j];
        for (uint32_t k = 0; k < 64; ++k) {
            if (s == 0) {
                v[k] = 1ull << (63 - k);
            } else if (k < s) {
                v[k] = (uint64_t)m[k] << (63 - k);
            } else {
                uint64_t x = v[k - s] ^ (v[k - s] >> s);
                for (uint32_t i = 1; i < s; ++i)
                    if ((poly >> (s - i)) & 1u) x ^= v[k - i];
                v[k] = x;
            }
        }
    }
    for (uint32_t j = 0; j < td; ++j) { /* the subsets of the first 8 direction numbers */
        t->low[j][0] = 0;
        for (uint32_t b = 1; b < 256; ++b) t->low[j][b] = t->low[j][b & (b - 1)] ^ t->v[j][udm1_ctz32(b)];
    }
    for (uint32_t j = 0; j < bd; ++j) /* ... and of numbers 0..7, 8..15, 16..23, 24..31 */
        for (int k = 0; k < 4; ++k) {
            t->bytes[j][k][0] = 0;
            for (uint32_t b = 1; b < 256; ++b)
                t->bytes[j][k][b] = t->bytes[j][k][b & (b - 1)] ^ t->v[j][8 * k + udm1_ctz32(b)];
            for (uint32_t b = 0; b < 256; ++b) t->rev[j][k][b] = udm1_reverse32((uint32_t)(t->bytes[j][k][b] >> 32));
        }
    seq->data = t;
    return UDM1_OK;
#else
    (void)seq;
    return udm1_fail(UDM1_ERROR_UNKNOWN_PRESET,
                     "udm1_seq_create: this libudm1 was built without the Sobol table (UDM1_SOBOL=OFF)");
#endif
}

const udm1_kind udm1_sobol_kind = {.name = "sobol", .value = sobol_value, .fill = sobol_fill, .base2 = sobol_base2, .base2_point = sobol_base2_point};

const void *udm1_sobol_stream_table(const udm1_seq_t *seq, int reversed, uint32_t *byte_dims)
{
    if (seq->kind != &udm1_sobol_kind) return NULL;
    const sobol *t = seq->data;
    *byte_dims = t->byte_dims;
    return reversed ? (const void *)&t->rev[0][0][0] : (const void *)&t->bytes[0][0][0];
}
