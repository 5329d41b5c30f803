// bench_per_sample.cpp - per-sample draws, udm1 against OpenQMC, in one process, alternating.
//
// Two protocols, each timed as the best of R rounds with udm1 and OpenQMC alternating inside a round:
//  - OpenQMC's own (its src/tools/lib/benchmark.cpp): S samples of one pixel, D dimensions each, drawn
//    four at a time, a new domain per draw (domain = domain.newDomain(0)); the values stored to a
//    volatile. udm1 runs it three ways: its domains (the same shape: child of the previous domain, a
//    4D draw), its stream draws (dimensions by index, 4 at a time, one udm1_stream per 64 dimensions,
//    filled once) and its cursor (udm1_cursor_start per sample, udm1_cursor_fill of 4).
//  - renderer-shaped: P pixels of a W x W image, N samples each, per sample a 2D camera draw and V
//    vertices of a 4D and a 2D draw (2 + 6 V dimensions); OpenQMC with a pixel sampler per sample and a
//    domain per decision, udm1 with a stream per pixel (filled once per pixel, timed with the draws)
//    and its domains as udm1-pt draws them (a vertex the next block, its 2D a child) or dimensions by
//    index.
// Prints one line per (protocol, sampler, way): nanoseconds per dimension drawn, and the matched
// OpenQMC sampler's time over it. Built and run by bench/bench_per_sample.py with -O3 -march=native,
// -O3 -march=x86-64-v3 and plain -O3; without OpenQMC (UDM1_NO_OPENQMC) it times udm1 alone.
//
//   bench_per_sample [--rounds R] [--samples S] [--dims D] [--width W] [--spp N] [--vertices V] [--sampler NAME]
#include <udm1/udm1.h>

#if !defined(UDM1_NO_OPENQMC)
#include <oqmc/oqmc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace {

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

volatile float sink_[4];

inline void save(const float s[4])
{
    sink_[0] = s[0], sink_[1] = s[1], sink_[2] = s[2], sink_[3] = s[3];
}

struct Options {
    int rounds = 5, samples = 32768, dims = 256, width = 128, spp = 16, vertices = 4;
};

// ---- OpenQMC's protocol ----------------------------------------------------------------------------

#if !defined(UDM1_NO_OPENQMC)
template <class Sampler> struct Oqmc {
    std::vector<unsigned char> cache;
    Oqmc() : cache(std::max<std::size_t>(Sampler::cacheSize, 1)) { Sampler::initialiseCache(cache.data()); }

    void openqmc_protocol(int samples, int dims) const
    {
        for (int i = 0; i < samples; ++i) {
            auto domain = Sampler(0, 0, 0, i, cache.data());
            for (int j = 0; j < dims; j += 4) {
                domain = domain.newDomain(0);
                float s[4] = {0, 0, 0, 0};
                domain.template drawSample<4>(s);
                save(s);
            }
        }
    }

    void renderer(int width, int spp, int vertices) const
    {
        for (int y = 0; y < width; ++y)
            for (int x = 0; x < width; ++x)
                for (int i = 0; i < spp; ++i) {
                    auto px = Sampler(x, y, 0, i, cache.data());
                    float s[4] = {0, 0, 0, 0};
                    px.newDomain(0).template drawSample<2>(s);
                    save(s);
                    for (int v = 0; v < vertices; ++v) {
                        auto vertex = px.newDomain(100 + v);
                        vertex.template drawSample<4>(s);
                        save(s);
                        vertex.newDomain(1).template drawSample<2>(s);
                        save(s);
                    }
                }
    }
};
#endif

// ---- udm1 -----------------------------------------------------------------------------------------

struct Udm1 {
    udm1_seq *seq = nullptr;
    uint32_t dims = 0;
    Udm1(const char *preset, uint32_t want, uint64_t k)
    {
        udm1_preset_info info;
        if (udm1_preset_find(preset, &info) != UDM1_OK) std::exit(2);
        dims = std::min(want, info.max_dimensions);
        if (udm1_seq_create(preset, dims, (info.flags & UDM1_PRESET_POINT_SET) ? k : 0, 1, &seq) != UDM1_OK) {
            std::fprintf(stderr, "bench_per_sample: %s: %s\n", preset, udm1_last_error());
            std::exit(2);
        }
    }
    ~Udm1() { udm1_seq_destroy(seq); }

    // OpenQMC's protocol with udm1's domains: a chain of children, a 4D draw each
    void domains(int samples, int ndims, const udm1_stream &st) const
    {
        for (int i = 0; i < samples; ++i) {
            udm1_domain d = udm1_domain_root(&st, (uint64_t)i);
            for (int j = 0; j < ndims; j += 4) {
                d = udm1_domain_child(d, 0);
                float s[4] = {0, 0, 0, 0};
                udm1_domain_draw_f32(d, 4, s);
                save(s);
            }
        }
    }
    // The domain design's alternatives, measured in the same protocol (a Weyl sequence's child chain, 4D
    // floats), each written with the AVX2 code the header's inline draw uses (built with -march=native
    // only). Variant 1: the domains as shipped, spelled out (a check of the spelling: it must time like
    // "domains"); 2: a child key of one multiply, (k ^ k >> 32) M, instead of the 64-bit finalizer, the
    // index scramble's seed then hashed off the chain; 3: the four shifts from one hash times per-dimension
    // odd constants (dependent shifts); 4 and 5 measure costs, not designs: without the index scramble
    // (siblings' samples would pair on lines), without the per-draw shift hashes (siblings would share
    // shifts).
#if defined(__AVX2__)
    void domain_variant(int variant, int samples, int ndims, const udm1_stream &st) const
    {
        const uint64_t G = UDM1_GOLDEN_GAMMA, M = 0xD6E8FEB86659FD93ull;
        const __m256i H = _mm256_loadu_si256((const __m256i *)st.a_hi), L = _mm256_loadu_si256((const __m256i *)st.a_lo);
        const __m256i B = _mm256_loadu_si256((const __m256i *)st.base), K = _mm256_loadu_si256((const __m256i *)st.dim_key);
        const __m256i S = _mm256_loadu_si256((const __m256i *)st.offset);
        for (int i = 0; i < samples; ++i) {
            uint64_t key = st.key;
            for (int j = 0; j < ndims; j += 4) {
                uint64_t seed_src;
                if (variant == 2) {
                    uint64_t k = key + G;
                    key = (k ^ (k >> 32)) * M;
                    seed_src = udm1_mix64(key);
                } else {
                    key = udm1_mix64(key + G);
                    seed_src = key;
                }
                uint32_t low = variant == 4 ? (uint32_t)i : udm1_owen_index32((uint32_t)i, (uint32_t)(seed_src >> 32));
                __m256i O;
                if (variant == 5)
                    O = S;
                else
                    O = _mm256_add_epi64(udm1_mix64x4_(key, st.dim_key), B);
                if (variant == 3) { /* h times odd per-dimension constants: lane products of 64 bits */
                    __m256i h = _mm256_set1_epi64x((long long)udm1_mix64(key)), c = _mm256_or_si256(K, _mm256_set1_epi64x(1));
                    __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(h, 32), c),
                                                     _mm256_mul_epu32(h, _mm256_srli_epi64(c, 32)));
                    O = _mm256_add_epi64(B, _mm256_add_epi64(_mm256_mul_epu32(h, c), _mm256_slli_epi64(cross, 32)));
                }
                __m256i N = _mm256_set1_epi64x((long long)low);
                __m256i h0 = _mm256_mul_epu32(N, H), h1 = _mm256_mul_epu32(N, _mm256_srli_epi64(H, 32));
                __m256i l0 = _mm256_mul_epu32(N, L), l1 = _mm256_mul_epu32(N, _mm256_srli_epi64(L, 32));
                __m256i carry = _mm256_srli_epi64(_mm256_add_epi64(l1, _mm256_srli_epi64(l0, 32)), 32);
                __m256i v = _mm256_add_epi64(_mm256_add_epi64(O, _mm256_add_epi64(h0, _mm256_slli_epi64(h1, 32))), carry);
                __m256i top = _mm256_srli_epi64(v, 40);
                __m128i lo32 = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(top, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
                float s[4] = {0, 0, 0, 0};
                _mm_storeu_ps(s, _mm_mul_ps(_mm_cvtepi32_ps(lo32), _mm_set1_ps(1.0f / 16777216.0f)));
                save(s);
            }
        }
    }
#endif
    // Candidates for the domains' per-draw cost, in every build (the header's portable and vector helpers):
    // the keys and first four shifts (O_j = o_j + mix64(key + K_j)) of the domains a caller derives the same
    // way in every sample, computed once (as a stream fill would) instead of per draw. A chain of `depth`
    // children of key 0 from the root (OpenQMC's protocol: what a stream of 64 dimensions has no room to
    // hold), or per block of the root chain its child of key 0 (the renderer's; the shipped stream holds
    // those, udm1/stream.h's UDM1_STREAM_CHILDREN). The values are the shipped domains' (checked once by
    // check_cached).
    struct Cached {
        uint64_t key[64];
        uint64_t off[64][4];
    };
    static void fill_chain(const udm1_stream &st, int depth, Cached &c)
    {
        udm1_domain d = udm1_domain_root(&st, 0);
        for (int t = 0; t < depth && t < 64; ++t) {
            d = udm1_domain_child(d, 0);
            c.key[t] = d.key;
            for (int j = 0; j < 4; ++j) c.off[t][j] = st.base[j] + udm1_mix64(d.key + st.dim_key[j]);
        }
    }
    static void fill_blocks(const udm1_stream &st, int blocks, Cached &c)
    {
        for (int b = 0; b < blocks && b < 64; ++b) {
            udm1_domain d = udm1_domain_child(udm1_domain_next(udm1_domain_root(&st, 0), (uint32_t)b), 0);
            c.key[b] = d.key;
            for (int j = 0; j < 4; ++j) c.off[b][j] = st.base[j] + udm1_mix64(d.key + st.dim_key[j]);
        }
    }
    // The index scramble's final bit reversal by a byte table (variant 3).
    static uint32_t reverse_bytes(uint32_t x)
    {
        static const struct T {
            unsigned char r[256];
            T() { for (int b = 0; b < 256; ++b) r[b] = (unsigned char)(udm1_reverse32((uint32_t)b) >> 24); }
        } t;
        return (uint32_t)t.r[x & 255] << 24 | (uint32_t)t.r[(x >> 8) & 255] << 16 | (uint32_t)t.r[(x >> 16) & 255] << 8 |
               t.r[x >> 24];
    }
    // One cached child draw of 4 floats at sample index i (rev = reverse32(i)); variant 1: the index scramble
    // as the header writes it; 2: reverse32(i) once per sample; 3: also the final reversal by a byte table;
    // 4: no index scramble (a cost, not a design).
    static inline void cached_draw(int variant, const udm1_stream &st, const Cached &c, int t, uint32_t i, uint32_t rev,
                                   float s[4])
    {
        uint64_t key = c.key[t];
        uint32_t low = variant == 1 ? udm1_owen_index32(i, (uint32_t)(key >> 32))
                       : variant == 2 ? udm1_reverse32(udm1_owen_hash32(rev, (uint32_t)(key >> 32)))
                       : variant == 3 ? reverse_bytes(udm1_owen_hash32(rev, (uint32_t)(key >> 32)))
                                      : i;
        uint64_t r[4];
        udm1_weyl4_32(st.a_hi, st.a_lo, c.off[t], low, r);
        for (int j = 0; j < 4; ++j) s[j] = udm1_raw_to_f32(r[j]);
    }
    void domain_cached(int variant, int samples, int ndims, const udm1_stream &st, const Cached &c) const
    {
        for (int i = 0; i < samples; ++i) {
            uint32_t rev = udm1_reverse32((uint32_t)i);
            for (int j = 0; j < ndims; j += 4) {
                float s[4] = {0, 0, 0, 0};
                cached_draw(variant, st, c, (j / 4) & 63, (uint32_t)i, rev, s);
                save(s);
            }
        }
    }
    // renderer-shaped with the vertices' children cached per pixel (the cache filled with the stream, timed)
    void renderer_cached(int variant, int width, int spp, int vertices) const
    {
        for (int y = 0; y < width; ++y)
            for (int x = 0; x < width; ++x) {
                udm1_stream st;
                udm1_stream_init(&st, seq, ((uint64_t)y << 32) | (uint32_t)x, 0, 4 + 4 * (uint32_t)vertices);
                Cached c;
                fill_blocks(st, 1 + vertices, c);
                for (int i = 0; i < spp; ++i) {
                    float s[4] = {0, 0, 0, 0};
                    udm1_stream_draw_f32(&st, (uint64_t)i, 0, 2, s);
                    save(s);
                    uint32_t rev = udm1_reverse32((uint32_t)i);
                    for (int v = 0; v < vertices; ++v) {
                        udm1_stream_draw_f32(&st, (uint64_t)i, 4 + 4 * (uint32_t)v, 4, s);
                        save(s);
                        cached_draw(variant, st, c, 1 + v, (uint32_t)i, rev, s);
                        save(s);
                    }
                }
            }
    }
    // The candidates' values against the shipped domains' (variants 1-3; the first 64 children, some samples).
    bool check_cached(const udm1_stream &st) const
    {
        Cached chain, blocks;
        fill_chain(st, 64, chain);
        fill_blocks(st, 16, blocks);
        for (uint32_t i : {0u, 1u, 2u, 3u, 5u, 1000u, 32767u, 0x80000001u})
            for (int variant = 1; variant <= 3; ++variant) {
                udm1_domain d = udm1_domain_root(&st, i);
                for (int t = 0; t < 64; ++t) {
                    d = udm1_domain_child(d, 0);
                    float a[4], b[4];
                    udm1_domain_draw_f32(d, 4, a);
                    cached_draw(variant, st, chain, t, i, udm1_reverse32(i), b);
                    if (std::memcmp(a, b, sizeof a) != 0) return false;
                    if (t < 16) {
                        udm1_domain_draw_f32(udm1_domain_child(udm1_domain_next(udm1_domain_root(&st, i), (uint32_t)t), 0), 4, a);
                        cached_draw(variant, st, blocks, t, i, udm1_reverse32(i), b);
                        if (std::memcmp(a, b, sizeof a) != 0) return false;
                    }
                }
            }
        return true;
    }
    // the same dimensions by index through streams of 64 dimensions (filled once, outside the timing)
    void streams(int samples, int ndims, const std::vector<udm1_stream> &st) const
    {
        for (int i = 0; i < samples; ++i)
            for (int j = 0; j < ndims; j += 4) {
                float s[4] = {0, 0, 0, 0};
                udm1_stream_draw_f32(&st[j / UDM1_STREAM_DIMS], (uint64_t)i, j % UDM1_STREAM_DIMS, 4, s);
                save(s);
            }
    }
    void cursor(int samples, int ndims) const
    {
        for (int i = 0; i < samples; ++i) {
            udm1_cursor c;
            udm1_cursor_start(&c, seq, 0, (uint64_t)i, 0);
            for (int j = 0; j < ndims; j += 4) {
                float s[4] = {0, 0, 0, 0};
                udm1_cursor_fill(&c, 4, s);
                save(s);
            }
        }
    }
    // renderer-shaped, dimensions by index: 0-1 camera, then 6 per vertex
    void renderer_streams(int width, int spp, int vertices) const
    {
        for (int y = 0; y < width; ++y)
            for (int x = 0; x < width; ++x) {
                udm1_stream st;
                udm1_stream_init(&st, seq, ((uint64_t)y << 32) | (uint32_t)x, 0, 2 + 6 * (uint32_t)vertices);
                for (int i = 0; i < spp; ++i) {
                    float s[4] = {0, 0, 0, 0};
                    udm1_stream_draw_f32(&st, (uint64_t)i, 0, 2, s);
                    save(s);
                    for (int v = 0; v < vertices; ++v) {
                        udm1_stream_draw_f32(&st, (uint64_t)i, 2 + 6 * v, 4, s);
                        save(s);
                        udm1_stream_draw_f32(&st, (uint64_t)i, 6 + 6 * v, 2, s);
                        save(s);
                    }
                }
            }
    }
    // renderer-shaped with domains, as udm1-pt draws them
    void renderer_domains(int width, int spp, int vertices) const
    {
        for (int y = 0; y < width; ++y)
            for (int x = 0; x < width; ++x) {
                udm1_stream st;
                udm1_stream_init(&st, seq, ((uint64_t)y << 32) | (uint32_t)x, 0, 4 + 4 * (uint32_t)vertices);
                for (int i = 0; i < spp; ++i) {
                    udm1_domain px = udm1_domain_root(&st, (uint64_t)i);
                    float s[4] = {0, 0, 0, 0};
                    udm1_domain_draw_f32(px, 2, s);
                    save(s);
                    for (int v = 0; v < vertices; ++v) {  // as udm1-pt: the vertex the next block, its extras a child
                        udm1_domain vertex = udm1_domain_next(px, 1 + (uint32_t)v);
                        udm1_domain_draw_f32(vertex, 4, s);
                        save(s);
                        udm1_domain_draw_f32(udm1_domain_child(vertex, 0), 2, s);
                        save(s);
                    }
                }
            }
    }
};

struct Row {
    std::string protocol, sampler, way, anchor;
    double values = 0, best = 1e30, anchor_best = 0;
    std::function<void()> run;
};

int arg(int argc, char **argv, const char *name, int dflt)
{
    for (int i = 1; i + 1 < argc; ++i)
        if (std::strcmp(argv[i], name) == 0) {
            int v = std::atoi(argv[i + 1]);
            if (v <= 0) {
                std::fprintf(stderr, "bench_per_sample: %s takes a positive whole number\n", name);
                std::exit(2);
            }
            return v;
        }
    return dflt;
}

}  // namespace

int main(int argc, char **argv)
{
    Options o;
    o.rounds = arg(argc, argv, "--rounds", o.rounds);
    o.samples = arg(argc, argv, "--samples", o.samples);
    o.dims = arg(argc, argv, "--dims", o.dims) / 4 * 4;
    o.width = arg(argc, argv, "--width", o.width);
    o.spp = arg(argc, argv, "--spp", o.spp);
    o.vertices = arg(argc, argv, "--vertices", o.vertices);
    const double protocol_values = (double)o.samples * o.dims;
    const double renderer_values = (double)o.width * o.width * o.spp * (2 + 6.0 * o.vertices);

    // udm1's samplers and the OpenQMC sampler each is compared with
    struct Pair { const char *udm1, *anchor; };
    static const Pair pairs[] = {{"wr", "lattice"},       {"rd", "lattice"},   {"wopt", "lattice"},
                                 {"sobol-owen", "sobol"}, {"pmj02", "pmj"},    {"pcg32", "lattice"}};
    std::vector<Udm1 *> seqs;
    std::vector<Row> rows;
#if !defined(UDM1_NO_OPENQMC)
    static const Oqmc<oqmc::LatticeSampler> lattice;
    static const Oqmc<oqmc::SobolSampler> sobol;
    static const Oqmc<oqmc::PmjSampler> pmj;
    static const Oqmc<oqmc::LatticeBnSampler> latticebn;
    static const Oqmc<oqmc::SobolBnSampler> sobolbn;
    static const Oqmc<oqmc::PmjBnSampler> pmjbn;
    auto anchor = [&](const std::string &name, const std::string &protocol) -> std::function<void()> {
        int S = o.samples, D = o.dims, W = o.width, N = o.spp, V = o.vertices;
        if (protocol == "openqmc") {
            if (name == "lattice") return [=] { lattice.openqmc_protocol(S, D); };
            if (name == "sobol") return [=] { sobol.openqmc_protocol(S, D); };
            if (name == "pmj") return [=] { pmj.openqmc_protocol(S, D); };
            if (name == "latticebn") return [=] { latticebn.openqmc_protocol(S, D); };
            if (name == "sobolbn") return [=] { sobolbn.openqmc_protocol(S, D); };
            return [=] { pmjbn.openqmc_protocol(S, D); };
        }
        if (name == "lattice") return [=] { lattice.renderer(W, N, V); };
        if (name == "sobol") return [=] { sobol.renderer(W, N, V); };
        if (name == "pmj") return [=] { pmj.renderer(W, N, V); };
        if (name == "latticebn") return [=] { latticebn.renderer(W, N, V); };
        if (name == "sobolbn") return [=] { sobolbn.renderer(W, N, V); };
        return [=] { pmjbn.renderer(W, N, V); };
    };
    for (const char *a : {"lattice", "sobol", "pmj", "latticebn", "sobolbn", "pmjbn"}) {
        rows.push_back({"openqmc", a, "OpenQMC", "", protocol_values, 1e30, 0, anchor(a, "openqmc")});
        rows.push_back({"renderer", a, "OpenQMC", "", renderer_values, 1e30, 0, anchor(a, "renderer")});
    }
#endif
    static std::vector<std::vector<udm1_stream>> streams;  // per sampler: pixel 0's streams of 64 dimensions
    streams.reserve(16);
    for (const Pair &p : pairs) {
        Udm1 *u = new Udm1(p.udm1, (uint32_t)o.dims, (uint64_t)std::max(o.samples, o.spp));
        seqs.push_back(u);
        int D = std::min<int>(o.dims, (int)u->dims / 4 * 4), S = o.samples, W = o.width, N = o.spp, V = o.vertices;
        streams.emplace_back();
        std::vector<udm1_stream> &st = streams.back();
        st.resize((D + UDM1_STREAM_DIMS - 1) / UDM1_STREAM_DIMS);
        for (size_t k = 0; k < st.size(); ++k) udm1_stream_init(&st[k], u->seq, 0, (uint32_t)(k * UDM1_STREAM_DIMS), UDM1_STREAM_DIMS);
        const std::vector<udm1_stream> *sp = &st;
        double pv = (double)S * D;
        rows.push_back({"openqmc", p.udm1, "domains", p.anchor, (double)S * o.dims, 1e30, 0,
                        [=] { u->domains(S, o.dims, (*sp)[0]); }});
        rows.push_back({"openqmc", p.udm1, "stream", p.anchor, pv, 1e30, 0, [=] { u->streams(S, D, *sp); }});
        rows.push_back({"openqmc", p.udm1, "cursor", p.anchor, pv, 1e30, 0, [=] { u->cursor(S, D); }});
        rows.push_back({"renderer", p.udm1, "domains", p.anchor, renderer_values, 1e30, 0,
                        [=] { u->renderer_domains(W, N, V); }});
        rows.push_back({"renderer", p.udm1, "stream", p.anchor, renderer_values, 1e30, 0,
                        [=] { u->renderer_streams(W, N, V); }});
    }
#if defined(__AVX2__)
    // the domain design's alternatives (wr; Udm1::domain_variant)
    {
        Udm1 *u = seqs[0];
        const udm1_stream *st0 = &streams[0][0];
        int S = o.samples, D = o.dims;
        static const char *names[] = {"", "d:spelled", "d:1mulkey", "d:1hash", "c:noindex", "c:noshift"};
        for (int v = 1; v <= 5; ++v)
            rows.push_back({"openqmc", "wr", names[v], "lattice", (double)S * D, 1e30, 0,
                            [=] { u->domain_variant(v, S, D, *st0); }});
    }
#endif
    // the domains' per-draw costs, cached (wr; Udm1::domain_cached, Udm1::renderer_cached), in every build
    {
        Udm1 *u = seqs[0];
        const udm1_stream *st0 = &streams[0][0];
        if (!u->check_cached(*st0)) {
            std::fprintf(stderr, "bench_per_sample: a cached domain candidate draws other values than the domains\n");
            return 1;
        }
        static Udm1::Cached chain;
        Udm1::fill_chain(*st0, 64, chain);
        int S = o.samples, D = o.dims, W = o.width, N = o.spp, V = o.vertices;
        static const char *names[] = {"", "d:cached", "d:cachrev", "d:cachtab", "c:cachnoix"};
        for (int v = 1; v <= 4; ++v) {
            rows.push_back({"openqmc", "wr", names[v], "lattice", (double)S * D, 1e30, 0,
                            [=] { u->domain_cached(v, S, D, *st0, chain); }});
            rows.push_back({"renderer", "wr", names[v], "lattice", renderer_values, 1e30, 0,
                            [=] { u->renderer_cached(v, W, N, V); }});
        }
    }
    // screen-space randomization against OpenQMC's blue-noise variants (wr)
    {
        udm1_seq_desc desc;
        udm1_seq_desc_init(&desc);
        desc.preset = "wr", desc.dimensions = 2 + 6 * (uint32_t)o.vertices, desc.seed = 1;
        desc.randomize = UDM1_RANDOMIZE_SCREEN, desc.screen_spp = (uint32_t)o.spp;
        Udm1 *u = new Udm1("wr", 4, 0);
        udm1_seq_destroy(u->seq);
        if (udm1_seq_create_desc(&desc, &u->seq) != UDM1_OK) return 2;
        seqs.push_back(u);
        int W = o.width, N = o.spp, V = o.vertices;
        rows.push_back({"renderer", "wr screen", "stream", "latticebn", renderer_values, 1e30, 0,
                        [=] { u->renderer_streams(W, N, V); }});
        rows.push_back({"renderer", "wr screen", "domains", "latticebn", renderer_values, 1e30, 0,
                        [=] { u->renderer_domains(W, N, V); }});
    }
    for (int i = 1; i + 1 < argc; ++i)  // --sampler NAME: that udm1 sampler's rows and their anchors only
        if (std::strcmp(argv[i], "--sampler") == 0) {
            std::string keep = argv[i + 1], anchor_of;
            for (const Row &row : rows)
                if (row.sampler == keep) anchor_of += " " + row.anchor + " ";
            rows.erase(std::remove_if(rows.begin(), rows.end(),
                                      [&](const Row &row) {
                                          return row.way == "OpenQMC" ? anchor_of.find(" " + row.sampler + " ") == std::string::npos
                                                                      : row.sampler != keep;
                                      }),
                       rows.end());
        }
    for (int r = 0; r < o.rounds; ++r)  // every row once per round, anchors among them
        for (Row &row : rows) {
            double t0 = now();
            row.run();
            row.best = std::min(row.best, now() - t0);
        }
    std::printf("# per-sample draws; best of %d rounds, rows alternating within each round; udm1 %s, kernels %s\n",
                o.rounds, udm1_version_string(), udm1_isa());
    std::printf("# openqmc protocol: %d samples x %d dimensions, 4 per draw; renderer: %dx%d pixels x %d spp x %d "
                "dimensions\n",
                o.samples, o.dims, o.width, o.width, o.spp, 2 + 6 * o.vertices);
    std::printf("%-9s %-12s %-8s %10s %-10s %12s\n", "protocol", "sampler", "way", "ns/dim", "anchor", "anchor/udm1");
    for (Row &row : rows) {
        double ns = row.best / row.values * 1e9, ratio = 0;
        for (const Row &a : rows)
            if (a.way == "OpenQMC" && a.protocol == row.protocol && a.sampler == row.anchor)
                ratio = (a.best / a.values) / (row.best / row.values);
        std::printf("%-9s %-12s %-8s %10.3f %-10s %12s\n", row.protocol.c_str(), row.sampler.c_str(), row.way.c_str(),
                    ns, row.anchor.empty() ? "-" : row.anchor.c_str(),
                    ratio > 0 ? std::to_string(ratio).substr(0, 5).c_str() : "-");
    }
    for (Udm1 *u : seqs) delete u;
    return 0;
}
