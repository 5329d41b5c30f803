// Mitsuba 3 sampler plugin "udm1": udm1's sequences at native speed in every variant.
//
// It draws what udm1.mitsuba's Python sampler draws, bit for bit as float32, lane by lane (its docstring
// is the contract: the stream of each pixel, the index of each sample, the dimension of each draw, the
// padding past D):
//  - scalar variants: Mitsuba seeds the sampler once per pixel (and pass) with a seed unique in the render;
//    that seed is the stream (udm1_streams of 16 dimensions each, filled at their first draw after seed()),
//    the count of advance() calls the index, and each draw is udm1_stream_draw_f32 (udm1/stream.h: inline
//    for the Weyl, Sobol and pmj02 presets).
//  - vector variants (llvm_*, cuda_*): lane k of a pass of P samples per pixel is pixel k / P and sample
//    pass P + k % P; the stream is render_seed 2^32 + pixel ("screen": (y << 32) | x, the render's seed
//    added to the sequence's). The Weyl presets are computed in Dr.Jit integer arrays from the sequence
//    contract (udm1/seq.h: the 128-bit product with dr::mul_hi, the documented hash of udm1/domain.h,
//    the permute's XOR, the Owen scrambling and the tent); Sobol and pmj02 (where udm1/stream.h draws them
//    inline) in Dr.Jit from the library's tables and each pixel's randomization words; the other presets
//    are filled by the library at a pass's first draw into a table of D float32 values per lane.
// Properties are checked when the scene loads: a bad one is refused with one line naming it.
// Only libudm1's public header (udm1/udm1.h) is used; libudm1 is linked in statically.

#include <mitsuba/core/properties.h>
#include <mitsuba/render/sampler.h>
#include <drjit/if_stmt.h>

#include <udm1/udm1.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

NAMESPACE_BEGIN(mitsuba)

namespace udm1mi {

constexpr uint64_t kGolden = UDM1_GOLDEN_GAMMA;
constexpr uint64_t kSeedSalt = 0x75646D3153454544ull;  // "udm1SEED": the sequence key's salt (udm1's hash)
constexpr uint64_t kOwenLowSalt = 0x4F57454E00000000ull;  // udm1_owen64's low-half salt ("OWEN")
constexpr uint64_t kU32 = 0xFFFFFFFFull;
constexpr uint32_t kDefaultDimensions = 64;
const char *const kRandomize[] = {"default", "none", "shift", "owen", "permute", "screen"};
const char *const kWeylPresets[] = {"wr", "wr-ao", "we", "wgr", "wmmr", "hwmmr", "rd", "golden", "wopt"};
constexpr const char *kTent = "+tent";

[[noreturn]] inline void fail(const std::string &message) { throw std::runtime_error("udm1 sampler: " + message); }

inline std::string quoted(const std::string &s) { return "'" + s + "'"; }

inline std::string repr_double(double v) {
    char buf[64];
    double a = std::fabs(v);  // Python's repr: the shortest digits, scientific from 1e16 and below 1e-4
    auto r = (a >= 1e16 || (a > 0 && a < 1e-4)) ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific)
                                                : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
    std::string s(buf, r.ptr);
    if (s.find_first_of(".eni") == std::string::npos) s += ".0";
    return s;
}

/// A property's value as Python would print it, and its type's name (for the refusals).
inline std::pair<std::string, std::string> shown(const Properties &p, const char *name) {
    using T = Properties::Type;
    switch (p.type(name)) {
        case T::Bool: return {p.get<bool>(name) ? "True" : "False", "bool"};
        case T::Integer: return {std::to_string(p.get<int64_t>(name)), "int"};
        case T::Float: return {repr_double(p.get<double>(name)), "float"};
        case T::String: return {quoted(p.get<std::string>(name)), "str"};
        default: p.mark_queried(name); return {"(" + p.as_string(name) + ")", "non-number"};
    }
}

/// An integer property in [lo, hi]; refused with one line naming it when it is anything else.
inline int64_t integer(const Properties &p, const char *name, int64_t def, int64_t lo, int64_t hi,
                       const std::string &why = "") {
    if (!p.has_property(name)) return def;
    if (p.type(name) == Properties::Type::Float) {
        double v = p.get<double>(name);
        if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) >= 9223372036854775808.0)
            fail(std::string(name) + " " + repr_double(v) + " is not in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "] (Mitsuba's integer properties hold at most 2^63 - 1: a larger integer "
                 "arrives as a float)");
    }
    if (p.type(name) != Properties::Type::Integer) {
        auto [value, type] = shown(p, name);
        fail(std::string(name) + " " + value + " is not an integer (a " + type + ")");
    }
    int64_t v = p.get<int64_t>(name);
    if (v < lo || v > hi)
        fail(std::string(name) + " " + std::to_string(v) + " is not in [" + std::to_string(lo) + ", " +
             std::to_string(hi) + "]" + (why.empty() ? "" : " (" + why + ")"));
    return v;
}

inline std::string string(const Properties &p, const char *name, const std::string &def) {
    if (!p.has_property(name)) return def;
    if (p.type(name) != Properties::Type::String) {
        auto [value, type] = shown(p, name);
        fail(std::string(name) + " " + value + " is not a string (a " + type + ")");
    }
    return p.get<std::string>(name);
}

/// Every property of the sampler, checked (udm1.mitsuba's docstring says what each is).
struct Options {
    std::string preset, randomize;
    bool point_set = false, weyl = false, tent = false;
    uint32_t sample_count = 4, dimensions = 0;
    uint64_t seed = 0;
    uint32_t film_width = 0, film_height = 0;

    explicit Options(const Properties &p) {
        preset = string(p, "preset", "wr");
        udm1_preset_info info;
        if (udm1_preset_find(preset.c_str(), &info) != UDM1_OK) {
            std::string names;
            for (size_t i = 0; i < udm1_preset_count(); ++i) {
                udm1_preset_get(i, &info);
                names += (i ? ", " : "") + std::string(info.name);
            }
            fail("preset " + quoted(preset) + " is not a udm1 preset (" + names + ", each also as NAME" + kTent + ")");
        }
        tent = preset.size() > std::strlen(kTent) &&
               preset.compare(preset.size() - std::strlen(kTent), std::string::npos, kTent) == 0;
        std::string base = tent ? preset.substr(0, preset.size() - std::strlen(kTent)) : preset;
        point_set = (info.flags & UDM1_PRESET_POINT_SET) != 0;
        weyl = std::find(std::begin(kWeylPresets), std::end(kWeylPresets), base) != std::end(kWeylPresets);
        randomize = string(p, "randomize", "default");
        if (std::find(std::begin(kRandomize), std::end(kRandomize), randomize) == std::end(kRandomize))
            fail("randomize " + quoted(randomize) + " is not one of default, none, shift, owen, permute, screen");
        sample_count = (uint32_t) integer(p, "sample_count", 4, 1, (int64_t) kU32);
        seed = (uint64_t) integer(p, "seed", 0, 0, INT64_MAX);
        dimensions = (uint32_t) integer(p, "dimensions", std::min(kDefaultDimensions, info.max_dimensions), 1,
                                        info.max_dimensions,
                                        "preset " + quoted(preset) + " has " + std::to_string(info.max_dimensions));
        film_width = (uint32_t) integer(p, "film_width", 0, 1, (int64_t) kU32);
        film_height = (uint32_t) integer(p, "film_height", 0, 1, (int64_t) kU32);
        if ((film_width == 0) != (film_height == 0))
            fail("film_width and film_height go together: the film's crop size (one of them is missing)");
    }
    bool screen() const { return randomize == "screen"; }
};

using SeqPtr = std::shared_ptr<udm1_seq>;

/// The udm1 sequence of a sampler: D dimensions, point sets of spp points, the fixed screen-space scheme at
/// spp samples per pixel; the library's refusal as one line naming the properties.
inline SeqPtr make_sequence(const Options &o, uint32_t spp, uint64_t extra_seed = 0, bool randomized = true) {
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.dimensions = o.dimensions;
    desc.preset = o.preset.c_str();
    desc.point_count = o.point_set ? spp : 0;
    desc.seed = o.seed + extra_seed;
    uint32_t code = UDM1_RANDOMIZE_DEFAULT;
    if (o.randomize == "none") code = UDM1_RANDOMIZE_NONE;
    else if (o.randomize == "shift") code = UDM1_RANDOMIZE_SHIFT;
    else if (o.randomize == "permute") code = UDM1_RANDOMIZE_PERMUTE;
    else if (o.randomize == "owen") code = UDM1_RANDOMIZE_OWEN;
    else if (o.randomize == "screen") code = UDM1_RANDOMIZE_SCREEN;
    desc.randomize = randomized ? code : UDM1_RANDOMIZE_NONE;
    desc.screen_spp = randomized && o.screen() ? spp : 0;
    udm1_seq *seq = nullptr;
    if (udm1_seq_create_desc(&desc, &seq) != UDM1_OK)
        fail("preset " + quoted(o.preset) + " with randomize " + quoted(o.randomize) + ", sample_count " +
             std::to_string(spp) + " and dimensions " + std::to_string(o.dimensions) + " is refused by udm1: " +
             udm1_last_error());
    return SeqPtr(seq, udm1_seq_destroy);
}

inline uint64_t mix64(uint64_t z) { return udm1_mix64(z); }

/// udm1's keys (udm1/seq.h): the sequence's S; a dimension's K_j and a stream's T below, after jmix64.
inline uint64_t seq_key(const udm1_seq *seq) { return mix64(udm1_seq_seed(seq) ^ kSeedSalt); }

// ---- the Dr.Jit forms of udm1's integer arithmetic (udm1/seq.h, udm1/stream.h, udm1/domain.h) ----
template <typename U64> U64 jmix64(U64 z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/// K_j = mix64(S + (j + 1) G) and T = mix64(mix64(stream + G) ^ S), in scalar or Dr.Jit integers
template <typename U64> U64 dim_key(const U64 &S, const U64 &j) { return jmix64<U64>(S + (j + 1ull) * kGolden); }

template <typename U64> U64 stream_key(const U64 &S, const U64 &stream) {
    return jmix64<U64>(jmix64<U64>(stream + kGolden) ^ S);
}

template <typename U64> U64 jspread(U64 v) {
    v = v & 0xFFFFFFFFull;
    v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
    v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
    v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    return (v | (v << 1)) & 0x5555555555555555ull;
}

template <typename U32> U32 jreverse32(U32 x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

template <typename U32> U32 jowen_hash32(U32 x, const U32 &seed) {
    x ^= x * 0x3D20ADEAu;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526C56u;
    x ^= x * 0x53A22864u;
    return x;
}

}  // namespace udm1mi

template <typename Float, typename Spectrum>
class Udm1Sampler final : public Sampler<Float, Spectrum> {
public:
    MI_IMPORT_BASE(Sampler, m_sample_count, m_samples_per_wavefront, m_wavefront_size, m_dimension_index)
    MI_IMPORT_TYPES()
    static constexpr bool Jit = dr::is_jit_v<Float>;

    explicit Udm1Sampler(const Properties &props) : Udm1Sampler(udm1mi::Options(props), props) { }

    // The loop state. Mitsuba's integrators hold the sampler in the state of their symbolic loops
    // (dr::while_loop), which traverses it: the dimension index must be traversed there, or every iteration
    // (every bounce) would draw the dimensions of the first. Mitsuba's base class traverses its members only
    // for frozen functions (JitFlag::EnableObjectTraversal), and then it does so itself.
    void traverse_1_cb_ro(void *payload, dr::detail::traverse_callback_ro fn) const override {
        if (jit_flag(JitFlag::EnableObjectTraversal)) return Base::traverse_1_cb_ro(payload, fn);
        if constexpr (Jit) dr::traverse_1_fn_ro(m_dimension_index, payload, fn);
    }
    void traverse_1_cb_rw(void *payload, dr::detail::traverse_callback_rw fn) override {
        if (jit_flag(JitFlag::EnableObjectTraversal)) return Base::traverse_1_cb_rw(payload, fn);
        if constexpr (Jit) dr::traverse_1_fn_rw(m_dimension_index, payload, fn);
    }

    ref<Base> fork() override { return new Udm1Sampler(*this, Fork{}); }
    ref<Base> clone() override { return new Udm1Sampler(*this); }

    void set_sample_count(uint32_t spp) override {
        if (spp < 1) udm1mi::fail("sample_count 0 is not in [1, 4294967295]");
        if (spp != m_sample_count || !m_seq) {
            m_seq = udm1mi::make_sequence(m_o, spp, m_seq_seed);  // (checked first)
            prepare_direct(spp);
        }
        Base::set_sample_count(spp);
    }

    void seed(UInt32 seed, uint32_t wavefront_size = (uint32_t) -1) override {
        if constexpr (!Jit) {
            Base::seed(seed, wavefront_size);
            // the pixel's streams are filled at their first draw, a block of kBlock dimensions at a time: most
            // paths end long before D
            m_stream_id = seed;
            m_filled = m_inited = 0;
            if (m_direct) m_stream_key = udm1mi::stream_key<uint64_t>(m_S, seed);
            m_index = 0;
            m_fast = 0;
        } else {
            uint64_t render_seed = dr::width(seed) ? (uint64_t) dr::slice(seed, 0) : 0;
            Base::seed(seed, wavefront_size);
            m_pass = 0;
            m_render_seed = render_seed;
            if (m_o.screen() && render_seed != m_seq_seed) {
                m_seq = udm1mi::make_sequence(m_o, m_sample_count, render_seed);
                m_seq_seed = render_seed;
            }
            // the state is made (and the wavefront checked) at a pass's first draw: after a render Mitsuba seeds
            // the sampler again with a wavefront of 1 to release its state, and draws nothing
            release();
        }
    }

    void advance() override {
        Base::advance();
        if constexpr (!Jit) {
            m_index += 1;
            // (block 0 is filled where m_fast is not 0; a direct fill's sequence has no point count)
            uint64_t K = m_direct ? 0 : m_streams[0].point_count;
            if (m_fast && (K == 0 || m_index < K)) m_m += 1;  // (the same blocks)
            else update_fast();
        } else {
            m_pass += 1;
            release();
        }
    }

    Float next_1d(Mask = true) override {
        if constexpr (!Jit) {
            float v;
            draw(m_dimension_index, 1, &v);
            m_dimension_index += 1;
            return v;
        } else {
            if (m_stale) setup();
            UInt32 j = m_dimension_index;
            m_dimension_index = j + 1;
            return value(j);
        }
    }

    Point2f next_2d(Mask active = true) override {
        if constexpr (!Jit) {
            float v[2];
            uint32_t j = m_dimension_index;
            if (j + 2 > m_fast && j % kBlock == kBlock - 1) {  // (across two blocks, not both filled)
                draw(j, 1, v);
                draw(j + 1, 1, v + 1);
            } else {
                draw(j, 2, v);
            }
            m_dimension_index += 2;
            return Point2f(v[0], v[1]);
        } else {
            Float x = next_1d(active);
            return Point2f(x, next_1d(active));
        }
    }

    std::string to_string() const override {
        return "Udm1Sampler[preset=" + m_o.preset + ", sample_count=" + std::to_string(m_sample_count) +
               ", randomize=" + randomization() + ", dimensions=" + std::to_string(m_o.dimensions) + "]";
    }

    MI_DECLARE_CLASS(Udm1Sampler)

private:
    struct Fork { };

    /// The base class reads sample_count and seed as 32-bit: it is given the checked sample count only (the
    /// udm1 seed is this sampler's; Mitsuba's own base seed is not used).
    static Properties base_properties(const udm1mi::Options &o) {
        Properties p;
        p.set("sample_count", (int64_t) o.sample_count);
        return p;
    }

    Udm1Sampler(const udm1mi::Options &o, const Properties &props) : Base(base_properties(o)), m_o(o) {
        (void) props;
        if (m_o.screen() && !Jit)
            udm1mi::fail("randomize 'screen' needs a vector variant (llvm_*, cuda_*): the scalar variants do not "
                         "tell a sampler its pixel's position");
        if (m_o.screen() && !m_o.film_width)
            udm1mi::fail("randomize 'screen' needs film_width and film_height (the film's crop size): the pixel's "
                         "position is its stream");
        m_seq = udm1mi::make_sequence(m_o, m_o.sample_count);
        prepare_direct(m_o.sample_count);
    }

    /// Scalar variants, a Weyl sequence with per-stream shifts and nothing else (no point count, no screen
    /// segment): a block's inline words are A_j and o_j + mix64(T + K_j), T the pixel's stream key, made here
    /// from A_j, o_j and K_j held per sequence (udm1/stream.h's contract) instead of by udm1_stream_init, whose
    /// stream also derives the keys and words of its child domains, which a Mitsuba sampler never draws and
    /// which cost about 3 % of a 4-spp render. Used only where block 0 of two streams equals udm1_stream_init's,
    /// word for word; else the streams fill the blocks.
    void prepare_direct(uint32_t spp) {
        if constexpr (!Jit) {
            m_direct = direct_words(spp);
            m_filled = m_inited = m_fast = 0;  // (the check's block is not a pixel's: seed() comes first)
        }
    }

    /// prepare_direct's words and their check; true where they hold.
    bool direct_words(uint32_t spp) {
        using namespace udm1mi;
        const udm1_seq *seq = m_seq.get();
        udm1_stream st;
        if (udm1_seq_randomization(seq) != UDM1_RANDOMIZE_SHIFT || udm1_stream_init(&st, seq, 0, 0, kBlock) != UDM1_OK ||
            !(st.flags & UDM1_STREAM_INLINE) || st.point_count || st.index_base)
            return false;
        SeqPtr plain = make_sequence(m_o, spp, 0, false);  // the base offsets o_j
        m_direct_dims = std::min<uint32_t>(udm1_seq_dimensions(seq), UDM1_STREAM_DIMS);
        m_S = seq_key(seq);
        for (uint32_t j = 0; j < m_direct_dims; ++j) {
            Direct &w = m_direct_words[j];
            if (udm1_seq_alpha(seq, j, &w.a_hi, &w.a_lo) != UDM1_OK || udm1_seq_offset(plain.get(), 0, j, &w.base) != UDM1_OK)
                return false;
            w.key = dim_key<uint64_t>(m_S, j);
        }
        for (uint64_t stream : {uint64_t(0), uint64_t(0x123456789ull)}) {  // (the check: two streams' block 0)
            if (udm1_stream_init(&st, seq, stream, 0, kBlock) != UDM1_OK) return false;
            m_stream_key = stream_key<uint64_t>(m_S, stream);
            fill_direct(0);
            for (uint32_t k = 0; k < st.held; ++k)
                if (m_weyl[k].a_hi != st.a_hi[k] || m_weyl[k].a_lo != st.a_lo[k] || m_weyl[k].offset != st.offset[k])
                    return false;
        }
        return true;
    }

    /// fork(): the same configuration and sequence, to be seeded
    Udm1Sampler(const Udm1Sampler &s, Fork) : Base(base_properties(s.m_o)), m_o(s.m_o), m_seq(s.m_seq),
                                              m_seq_seed(s.m_seq_seed) {
        this->m_sample_count = s.m_sample_count;
        if constexpr (Jit) m_render_seed = s.m_render_seed;
        else {  // (prepare_direct's, for the same sequence)
            m_direct = s.m_direct, m_direct_dims = s.m_direct_dims, m_S = s.m_S;
            std::copy(std::begin(s.m_direct_words), std::end(s.m_direct_words), std::begin(m_direct_words));
        }
    }

    /// clone(): the same state, the same future draws (the stream and the arrays are values)
    Udm1Sampler(const Udm1Sampler &s) = default;

    /// The randomization applied (the preset's default resolved), as udm1.Sequence.randomization names it.
    std::string randomization() const {
        switch (udm1_seq_randomization(m_seq.get())) {
            case UDM1_RANDOMIZE_NONE: return "none";
            case UDM1_RANDOMIZE_SHIFT: return "shift";
            case UDM1_RANDOMIZE_PERMUTE: return "permute";
            case UDM1_RANDOMIZE_OWEN: return "owen";
            case UDM1_RANDOMIZE_SCREEN: return "screen";
            default: return "default";
        }
    }

    /// Scalar variants: dimensions [j, j + n) of the current sample, within one block of kBlock dimensions
    /// below UDM1_STREAM_DIMS (a Weyl value inline here: the contract's arithmetic on the stream's words,
    /// udm1/stream.h), or past them (the library's draw: the sequence's value or its padding).
    void draw(uint32_t j, uint32_t n, float *out) {
        if (j + n <= m_fast) {  // (j < 2^32 - 2: j + n does not wrap)
            for (uint32_t k = 0; k < n; ++k) {
                const Weyl &w = m_weyl[j + k];
                out[k] = udm1_raw_to_f32(udm1_weyl_value(w.a_hi, w.a_lo, w.offset, m_m));  // (two 64-bit products)
            }
            return;
        }
        draw_library(j, n, out);
    }

    /// m_fast: how many of the sample's first dimensions draw inline (m_weyl at the index m_m): the filled blocks
    /// from the first on, while their sequence is a Weyl one held there and the index inside a point set. After
    /// seed(), a fill and advance().
    void update_fast() {
        m_fast = 0;
        if (m_direct) {  // (the index is the sample's: no point count, no segment)
            m_m = m_index;
            for (uint32_t b = 0; b < kBlocks && (m_filled & (1u << b)); ++b) {
                m_fast = b * kBlock + m_held[b];
                if (m_held[b] < kBlock) return;
            }
            return;
        }
        for (uint32_t b = 0; b < kBlocks && (m_filled & (1u << b)); ++b) {
            const udm1_stream &st = m_streams[b];
            uint64_t m = m_index + st.index_base;
            if (!(st.flags & UDM1_STREAM_INLINE) || (st.point_count && m_index >= st.point_count) || (b && m != m_m))
                return;
            m_m = m;
            m_fast = b * kBlock + st.held;
            if (st.held < kBlock) return;
        }
    }

    /// draw() past its inline case: the block filled at its first draw, then udm1_stream_draw_f32 (inline for
    /// Sobol and pmj02, a library call for the other kinds and past the blocks).
    MI_NOINLINE void draw_library(uint32_t j, uint32_t n, float *out) {
        uint32_t b = j / kBlock < kBlocks ? j / kBlock : 0;  // (past the blocks: the library's draw from block 0)
        udm1_stream &st = m_streams[b];
        if (!(m_filled & (1u << b))) {
            for (uint32_t e = 0; e <= b; ++e)  // (the blocks before it too: the inline draws run from the first)
                if (!(m_filled & (1u << e))) fill_block(e);
            update_fast();
            if (j + n <= m_fast) {
                draw(j, n, out);
                return;
            }
        }
        if (!(m_inited & (1u << b))) init_stream(b);  // (a direct fill's block: its stream made when it draws)
        udm1_stream_draw_f32(&st, m_index, j - st.first, n, out);
        if (std::isnan(out[0])) refused_draw();
    }

    MI_NOINLINE void fill_block(uint32_t b) {
        if (m_direct) {
            fill_direct(b);
            return;
        }
        init_stream(b);
        m_filled |= 1u << b;
        const udm1_stream &st = m_streams[b];
        m_held[b] = st.held;
        if (st.flags & UDM1_STREAM_INLINE)  // a dimension's three words side by side
            for (uint32_t k = 0; k < st.held; ++k)
                m_weyl[b * kBlock + k] = {st.a_hi[k], st.a_lo[k], st.offset[k]};
    }

    /// Block b's inline words made by the plugin (prepare_direct): o_j + mix64(T + K_j), four at a time.
    void fill_direct(uint32_t b) {
        uint32_t first = b * kBlock, held = first < m_direct_dims ? std::min(kBlock, m_direct_dims - first) : 0;
        for (uint32_t k = 0; k < held; k += 4) {
            uint64_t key[4] = {}, word[4];
            for (uint32_t i = 0; i < 4 && k + i < held; ++i) key[i] = m_direct_words[first + k + i].key;
            udm1_mix64x4(m_stream_key, key, word);
            for (uint32_t i = 0; i < 4 && k + i < held; ++i) {
                const Direct &w = m_direct_words[first + k + i];
                m_weyl[first + k + i] = {w.a_hi, w.a_lo, w.base + word[i]};
            }
        }
        m_held[b] = held;
        m_filled |= 1u << b;
    }

    void init_stream(uint32_t b) {
        if (udm1_stream_init(&m_streams[b], m_seq.get(), m_stream_id, b * kBlock, kBlock) != UDM1_OK)
            udm1mi::fail("stream " + std::to_string(m_stream_id) + ": " + udm1_last_error());
        m_inited |= 1u << b;
    }

    [[noreturn]] MI_NOINLINE void refused_draw() const {
        udm1mi::fail("sample " + std::to_string(m_index) + " of stream " + std::to_string(m_stream_id) +
                     " cannot be drawn: " + udm1_last_error());
    }

    // ---- vector variants ----
    void release() {
        m_stale = true;
        m_key = m_n = m_idx = m_pkey = UInt64();
        m_zero = UInt32();
        m_ahi = m_alo = m_base = m_dim_key = UInt64();
        m_table = Float();
        m_lane = UInt32();
        m_inline = 0;
        m_table64 = UInt64();
        m_table32 = m_g = UInt32();
    }

    /// Per-lane state of a pass: stream ids and sample indices, and what the draws read.
    void setup() {
        using namespace udm1mi;
        uint32_t lanes = m_wavefront_size, spp = m_sample_count, per_pass;
        if (m_o.film_width) {
            uint64_t pixels = (uint64_t) m_o.film_width * m_o.film_height;
            if (lanes == 0 || lanes % pixels || spp % (lanes / pixels))
                fail("a wavefront of " + std::to_string(lanes) + " samples is not film_width x film_height (" +
                     std::to_string(m_o.film_width) + " x " + std::to_string(m_o.film_height) +
                     ") times a divisor of sample_count " + std::to_string(spp) + " (film_width and film_height are "
                     "the film's crop size, plus twice the filter's border with sample_border)");
            per_pass = (uint32_t) (lanes / pixels);
        } else {
            per_pass = m_samples_per_wavefront;
            if (lanes == 0 || per_pass == 0 || lanes % per_pass)
                fail("a wavefront of " + std::to_string(lanes) + " samples is not a multiple of the samples per "
                     "pass " + std::to_string(per_pass));
        }
        m_stale = false;
        UInt32 lane = dr::arange<UInt32>(lanes), pixel = lane / per_pass;
        // per-render numbers enter the kernels as opaque parameters, not literals: one compilation serves every
        // render seed and pass
        UInt64 sample = dr::opaque<UInt64>((uint64_t) m_pass * per_pass) + UInt64(lane % per_pass);
        bool screen = m_o.screen();
        UInt64 stream = screen ? (UInt64(pixel / m_o.film_width) << 32) | UInt64(pixel % m_o.film_width)
                               : (dr::opaque<UInt64>(m_render_seed) << 32) + UInt64(pixel);
        const udm1_seq *seq = m_seq.get();
        uint32_t d = udm1_seq_dimensions(seq);
        m_d = dr::opaque<UInt32>(d);
        m_mode = udm1_seq_randomization(seq);
        uint64_t S = seq_key(seq);
        m_S = dr::opaque<UInt64>(S);
        m_key = stream_key<UInt64>(m_S, stream);
        m_n = sample;
        m_zero = dr::opaque<UInt32>(0u, lanes);  // (a stored 0 a lane, not a literal: the sum is not folded away)
        m_pkey = screen ? stream : m_key;  // padding hashes the stream key (in screen mode the stream)
        std::vector<uint64_t> keys(d);  // the dimensions' K_j: the Weyl shifts' and the base-2 words' keys
        for (uint32_t j = 0; j < d; ++j) keys[j] = dim_key<uint64_t>(S, j);
        m_dim_key = dr::load<UInt64>(keys.data(), d);
        if (m_o.weyl) {
            SeqPtr plain = make_sequence(m_o, m_sample_count, 0, false);  // the base offsets o_j
            std::vector<uint64_t> ahi(d), alo(d), base(d);
            for (uint32_t j = 0; j < d; ++j) {
                if (udm1_seq_alpha(seq, j, &ahi[j], &alo[j]) != UDM1_OK ||
                    udm1_seq_offset(plain.get(), 0, j, &base[j]) != UDM1_OK)
                    fail(std::string("dimension ") + std::to_string(j) + ": " + udm1_last_error());
                if (screen)  // the fixed scheme's one shift u_j = mix(S + K_j)
                    base[j] += mix64(S + keys[j]);
            }
            m_ahi = dr::load<UInt64>(ahi.data(), d);
            m_alo = dr::load<UInt64>(alo.data(), d);
            m_base = dr::load<UInt64>(base.data(), d);
            auto morton = [](const UInt64 &s) { return jspread<UInt64>(s) | (jspread<UInt64>(s >> 32) << 1); };
            m_idx = screen ? sample + morton(stream) * dr::opaque<UInt64>((uint64_t) spp) : sample;
            // whether every index is below 2^32 (a pixel's samples always are; in screen mode the pixel's Morton
            // code times spp, bounded by the film's side rounded up to a power of two): the Weyl value then takes
            // 32 x 32-bit products (udm1_weyl_value32), the same bits as the 64-bit ones
            uint64_t side = 1;
            while (side < std::max(m_o.film_width, m_o.film_height)) side <<= 1;
            m_idx32 = !screen || (side <= 65536 && (side * side) <= (0xFFFFFFFFull + 1) / std::max<uint64_t>(spp, 1));
        } else if (!inline_tables(sample, d)) {
            fill_table(stream, sample, lanes, d);
        }
    }

    /// Sobol (any randomization but the tent) and pmj02 (unrandomized or digitally shifted), the cases
    /// udm1/stream.h draws inline, drawn the same way in Dr.Jit: the library's table of the sequence (its
    /// layout is the header's) and each pixel's randomization words, udm1_stream_init's (the hash of the
    /// stream's key and the dimension's, as a Weyl shift: made per value, not stored per pixel). False
    /// (nothing set) where the stream does not draw its D dimensions inline.
    bool inline_tables(const UInt64 &sample, uint32_t d) {
        const udm1_seq *seq = m_seq.get();
        udm1_stream st;
        if (d > UDM1_STREAM_DIMS || udm1_stream_init(&st, seq, 0, 0, d) != UDM1_OK || st.held != d) return false;
        bool sobol = (st.flags & UDM1_STREAM_SOBOL) && d <= st.table_bits, pmj02 = (st.flags & UDM1_STREAM_PMJ02) != 0;
        if (!sobol && !pmj02) return false;
        uint32_t mode = st.table_mode;
        m_inline = sobol ? 1 : 2;
        m_table_mode = mode;
        UInt32 index = UInt32(sample);  // (below 2^32: a Sobol index; below K: a pmj02 one)
        if (sobol) {
            m_g = index ^ (index >> 1);  // the Gray code
            // the Gray code's bytes that can be non-zero: every index is below the sample count (a byte of 0
            // selects no direction number: its table entry is 0)
            uint32_t bits = 0;
            for (uint64_t top = (uint64_t) m_sample_count - 1; top; top >>= 1) ++bits;
            m_gray_bytes = std::max(1u, (bits + 7) / 8);
            if (mode == 2)
                m_table32 = dr::load<UInt32>((const uint32_t *) st.table, (size_t) d * 4 * 256);
            else
                m_table64 = dr::load<UInt64>((const uint64_t *) st.table, (size_t) d * 4 * 256);
        } else {
            uint64_t K = st.point_count, blocks = (d + 3) / 4;
            m_g = index;
            m_table32 = dr::load<UInt32>((const uint32_t *) st.table, (size_t) (blocks * K * 4));
            m_K = dr::opaque<UInt32>((uint32_t) K);
        }
        return true;
    }

    /// The randomization word of dimension jj < D per lane: udm1_shift(T, K_j) of the stream's key T and the
    /// dimension's held key (a Weyl shift, and the base-2 kinds' word, as udm1_stream_init finds them).
    UInt64 word_of(const UInt32 &jj) const {
        return udm1mi::jmix64<UInt64>(m_key + dr::gather<UInt64>(m_dim_key, jj));
    }

    /// The float32 value of dimension jj < D per lane from the inline tables.
    Float inline_value(const UInt32 &jj) const {
        UInt64 word = word_of(jj);  // (mode 0: not read)
        UInt32 top;
        if (m_inline == 1) {  // Sobol: the XOR of the direction numbers the Gray code's four bytes select
            UInt32 at = jj * 1024u;
            auto entry = [&](uint32_t b) { return at + 256u * b + ((m_g >> (8u * b)) & 255u); };  // byte b's
            if (m_table_mode == 2) {  // reversed top halves, Owen-scrambled by the word's low half
                UInt32 rev = dr::gather<UInt32>(m_table32, entry(0));
                for (uint32_t b = 1; b < m_gray_bytes; ++b) rev = rev ^ dr::gather<UInt32>(m_table32, entry(b));
                top = udm1mi::jreverse32<UInt32>(udm1mi::jowen_hash32<UInt32>(rev, UInt32(word & 0xFFFFFFFFull)));
            } else {
                UInt64 v = dr::gather<UInt64>(m_table64, entry(0));
                for (uint32_t b = 1; b < m_gray_bytes; ++b) v = v ^ dr::gather<UInt64>(m_table64, entry(b));
                if (m_table_mode == 1) v = v ^ word;
                top = UInt32(v >> 32);
            }
        } else {  // pmj02: the point's coordinate in its block of four, XORed with the word's high half
            top = dr::gather<UInt32>(m_table32, ((jj >> 2) * m_K + m_g) * 4u + (jj & 3u));
            if (m_table_mode == 1) top = top ^ UInt32(word >> 32);
        }
        return Float(top >> 8) * (1.f / 16777216.f);
    }

    /// The library's values of every lane for dimensions [0, D): D float32 columns, one udm1_stream per pixel
    /// run of lanes, on every core.
    void fill_table(const UInt64 &stream, const UInt64 &sample, uint32_t lanes, uint32_t d) {
        std::vector<uint64_t> s(lanes), n(lanes);
        dr::store(s.data(), stream);
        dr::store(n.data(), sample);
        std::vector<float> table((size_t) d * lanes);
        const udm1_seq *seq = m_seq.get();
        std::string error;
        auto work = [&](uint32_t a, uint32_t b, std::string *err) {
            udm1_stream st;
            std::vector<float> v(d);
            bool started = false;
            for (uint32_t k = a; k < b; ++k) {
                if (!started || s[k] != st.stream) {
                    if (udm1_stream_init(&st, seq, s[k], 0, std::min<uint32_t>(d, UDM1_STREAM_DIMS)) != UDM1_OK) {
                        *err = udm1_last_error();
                        return;
                    }
                    started = true;
                }
                udm1_stream_draw_f32(&st, n[k], 0, d, v.data());
                if (std::isnan(v[0])) {
                    *err = "sample " + std::to_string(n[k]) + " of stream " + std::to_string(s[k]) + ": " +
                           udm1_last_error();
                    return;
                }
                for (uint32_t j = 0; j < d; ++j) table[(size_t) j * lanes + k] = v[j];
            }
        };
        uint32_t workers = std::max(1u, std::min<uint32_t>(std::thread::hardware_concurrency(), lanes / 4096));
        std::vector<std::string> errors(workers);
        std::vector<std::thread> threads;
        for (uint32_t w = 1; w < workers; ++w)
            threads.emplace_back(work, (uint32_t) ((uint64_t) lanes * w / workers),
                                 (uint32_t) ((uint64_t) lanes * (w + 1) / workers), &errors[w]);
        work(0, (uint32_t) ((uint64_t) lanes / workers), &errors[0]);
        for (auto &t : threads) t.join();
        for (auto &e : errors)
            if (!e.empty()) udm1mi::fail(e);
        m_table = dr::load<Float>(table.data(), table.size());
        m_lanes = dr::opaque<UInt32>(lanes);
        m_lane = dr::arange<UInt32>(lanes);
    }

    /// Raw 64-bit value of Weyl dimension jj < D per lane, the randomization applied.
    UInt64 weyl_raw(const UInt32 &jj) const {
        using namespace udm1mi;
        UInt64 ahi = dr::gather<UInt64>(m_ahi, jj), alo = dr::gather<UInt64>(m_alo, jj),
               base = dr::gather<UInt64>(m_base, jj);
        UInt64 word;
        if (m_mode == UDM1_RANDOMIZE_SHIFT || m_mode == UDM1_RANDOMIZE_PERMUTE || m_mode == UDM1_RANDOMIZE_OWEN)
            word = word_of(jj);
        if (m_mode == UDM1_RANDOMIZE_SHIFT) base = base + word;
        UInt64 raw;
        if (m_idx32) {  // (udm1_weyl_value32: the index's high half known to be 0, the four products 32 x 32-bit)
            const uint64_t lo32 = 0xFFFFFFFFull;
            UInt64 n = m_idx & lo32;
            UInt64 h0 = n * (ahi & lo32), h1 = n * (ahi >> 32), l0 = n * (alo & lo32), l1 = n * (alo >> 32);
            raw = base + h0 + (h1 << 32) + ((l1 + (l0 >> 32)) >> 32);
        } else {
            raw = base + m_idx * ahi + dr::mul_hi(m_idx, alo);
        }
        if (m_mode == UDM1_RANDOMIZE_PERMUTE) {
            raw = raw ^ word;
        } else if (m_mode == UDM1_RANDOMIZE_OWEN) {  // udm1_owen64 (udm1/stream.h's Sobol form)
            UInt64 top = UInt64(jreverse32<UInt32>(
                jowen_hash32<UInt32>(jreverse32<UInt32>(UInt32(raw >> 32)), UInt32(word & 0xFFFFFFFFull))));
            UInt64 low = jmix64<UInt64>(((top << 32) | (word >> 32)) ^ kOwenLowSalt) & 0xFFFFFFFFull;
            raw = (top << 32) | low;
        }
        if (m_o.tent) {  // udm1_tent: 2x below 1/2, 2 - 2x above, exactly on the 0.64 value
            UInt64 top = UInt64(0) - (raw >> 63);
            raw = ((raw ^ top) - top) << 1;
        }
        return raw;
    }

    /// Dimension j (per lane) of each lane's point, as float32: the sequence's value inside its D dimensions,
    /// the padding past them. A symbolic conditional: the kernel runs a side only where a lane takes it, so the
    /// padding's two hashes cost nothing while every lane is inside (a path's dimensions usually are).
    Float value(const UInt32 &j_) const {
        using namespace udm1mi;
        UInt32 j = j_;  // (the conditional runs over every lane: an index the same in all, of width 1, widened)
        if (dr::width(j) != dr::width(m_zero)) j = j + m_zero;
        auto inside = j < m_d;
        UInt32 jj = dr::minimum(j, m_d - 1u);
        auto to_f32 = [](const UInt64 &raw) { return Float(UInt32(raw >> 40)) * (1.f / 16777216.f); };
        auto padding = [this, to_f32](const UInt32 &, const UInt32 &jp) {  // udm1_pad of udm1_dim_key(S, j)
            UInt64 k = dim_key<UInt64>(m_S, UInt64(jp));
            return to_f32(jmix64<UInt64>(jmix64<UInt64>(m_pkey + k) + (m_n + 1ull) * kGolden));
        };
        auto sequence = [this, to_f32](const UInt32 &d, const UInt32 &) -> Float {
            if (m_o.weyl) return to_f32(weyl_raw(d));
            if (m_inline) return inline_value(d);
            return dr::gather<Float>(m_table, d * m_lanes + m_lane);
        };
        return dr::if_stmt(dr::make_tuple(jj, j), inside, sequence, padding, "udm1 value");
    }

    udm1mi::Options m_o;
    udm1mi::SeqPtr m_seq;
    uint64_t m_seq_seed = 0;  // the render's seed added to the sequence's ("screen", vector variants)
    // scalar variants
    static constexpr uint32_t kBlock = 16, kBlocks = UDM1_STREAM_DIMS / kBlock;
    udm1_stream m_streams[kBlocks]{};  // dimensions [16 b, 16 b + 16) of the pixel's stream, filled when drawn
    uint32_t m_filled = 0;             // which of them are (their inline words in m_weyl where Weyl)
    uint32_t m_inited = 0;             // which of m_streams are made (a direct fill makes one when it draws)
    uint32_t m_held[kBlocks]{};        // the dimensions a filled block holds
    struct Direct { uint64_t a_hi, a_lo, base, key; };
    bool m_direct = false;             // blocks filled from m_direct_words (prepare_direct)
    uint32_t m_direct_dims = 0;
    uint64_t m_stream_key = 0;         // the pixel's stream key T (direct fills)
    Direct m_direct_words[UDM1_STREAM_DIMS]{};  // A_j, o_j and K_j of the sequence's first dimensions
    uint32_t m_fast = 0;               // the dimensions drawn inline and their index (update_fast)
    uint64_t m_m = 0;
    struct Weyl { uint64_t a_hi, a_lo, offset; };
    Weyl m_weyl[UDM1_STREAM_DIMS];     // a Weyl sequence's: A_j and the pixel's O_j, dimension by dimension
    uint64_t m_stream_id = 0, m_index = 0;
    // vector variants
    bool m_stale = true;
    uint32_t m_pass = 0, m_mode = 0;
    uint64_t m_render_seed = 0;
    UInt64 m_S, m_key, m_n, m_idx, m_pkey, m_ahi, m_alo, m_base, m_dim_key;
    UInt32 m_d, m_lanes, m_lane, m_zero;
    Float m_table;
    bool m_idx32 = false;  // every Weyl index below 2^32 (setup)
    uint32_t m_gray_bytes = 4;  // the Sobol Gray code's bytes that can be non-zero (inline_tables)
    uint32_t m_inline = 0, m_table_mode = 0;  // inline tables: 1 Sobol, 2 pmj02 (else 0)
    UInt64 m_table64;
    UInt32 m_table32, m_g, m_K;
};

#if defined(UDM1_MITSUBA_TEST_VARIANTS)
// only scalar_rgb and llvm_ad_rgb: the tests' build (a third of the compile time)
extern "C" MI_EXPORT void init_plugin(std::string_view name, PluginRegisterFn fn) {
    using FL = dr::DiffArray<JitBackend::LLVM, float>;
    using S = Udm1Sampler<float, Color<float, 3>>;
    using L = Udm1Sampler<FL, Color<FL, 3>>;
    fn(name, "scalar_rgb", S::Type, [](void *, const Properties &p) -> ref<Object> { return new S(p); });
    fn(name, "llvm_ad_rgb", L::Type, [](void *, const Properties &p) -> ref<Object> { return new L(p); });
}
#else
MI_EXPORT_PLUGIN(Udm1Sampler)
#endif
NAMESPACE_END(mitsuba)
