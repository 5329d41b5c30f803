// udm1_pbrt_sampler.h - a udm1 sequence behind pbrt-v4's sampler interface (StartPixelSample, Get1D,
// Get2D, GetPixel2D), through libudm1's public header only. pbrt-v4's UDM1Sampler (added by
// udm1-sampler.patch beside this file) forwards to it; it has no other dependency, so udm1's tests check
// it without pbrt.
//
// Layout, as pbrt-v4's own low-discrepancy samplers: pixel (x, y) is udm1 stream ((uint64_t)y << 32) | x
// (the stream id udm1's screen-space randomization expects), sample i is the sequence's point i of that
// stream, GetPixel2D draws dimensions 0 and 1, and Get1D / Get2D hand out dimensions from 2 upward (from
// StartPixelSample's `dimension` when it is larger, as pbrt-v4's wavefront integrator restarts a sample
// at a known dimension). Past the sequence's own dimensions the values are udm1's padding (independent
// hashed uniforms, as udm1_cursor gives). Values are udm1's documented conversions of the exact 0.64
// fixed-point values: floats the top 24 bits, doubles the top 53, always below 1.
//
// A pixel's stream (its shifts or randomization words, udm1_stream_init) is found once when the pixel
// changes: pbrt-v4 renders a pixel's samples of a wave one after the other. The sequence is shared by all
// clones (const udm1_seq handles are thread-safe); each clone keeps its own stream and counters.
//
// What a scene may ask (create_for_scene): every udm1 preset, also with the tent ("NAME+tent"), except
// those of fewer than the 2 dimensions a pixel sample needs (golden, epis); every randomization the
// library gives that preset (screen: the Weyl sequences only); seeds 0 .. 2^31 - 1 (pbrt's integers;
// a negative seed is refused, not wrapped); at least 1 sample per pixel, and for a point set at most the
// library's K for that preset. Anything else is refused when the scene is read, with one line naming it.
// A draw the library cannot make (a sample index at or past a point set's K) is NaN, never another
// point's value.
#pragma once

#include <udm1/udm1.h>

#include <cstdint>
#include <memory>
#include <string>

namespace udm1pbrt {

// The randomization names a scene file may give ("string randomization"), as udm1-seq and udm1-pt spell
// them; false for another name.
inline bool randomization_from_name(const std::string &name, uint32_t *out)
{
    static const struct {
        const char *name;
        udm1_randomize value;
    } names[] = {{"default", UDM1_RANDOMIZE_DEFAULT}, {"none", UDM1_RANDOMIZE_NONE},
                 {"shift", UDM1_RANDOMIZE_SHIFT},     {"permute", UDM1_RANDOMIZE_PERMUTE},
                 {"owen", UDM1_RANDOMIZE_OWEN},       {"screen", UDM1_RANDOMIZE_SCREEN}};
    for (const auto &n : names)
        if (name == n.name) return *out = (uint32_t)n.value, true;
    return false;
}

struct SeqDeleter {
    void operator()(udm1_seq *s) const { udm1_seq_destroy(s); }
};
using SharedSeq = std::shared_ptr<const udm1_seq>;

// The sequence a scene's Sampler "udm1" asks for: a preset, a randomization, a seed and the samples per
// pixel (a point set's K; screen-space randomization's N). The dimensions are the preset's own (at most
// 64: the rest are padding); a preset with fewer than 2 is refused. On failure returns null and sets
// *error to udm1's one-line message.
inline SharedSeq create_sequence(const std::string &preset, uint32_t randomize, uint64_t seed, uint32_t spp,
                                 std::string *error)
{
    udm1_preset_info info;
    if (udm1_preset_find(preset.c_str(), &info) != UDM1_OK) {
        *error = udm1_last_error();
        return nullptr;
    }
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = preset.c_str();
    desc.dimensions = info.max_dimensions < UDM1_STREAM_DIMS ? info.max_dimensions : UDM1_STREAM_DIMS;
    desc.point_count = (info.flags & UDM1_PRESET_POINT_SET) ? spp : 0;
    desc.seed = seed;
    desc.randomize = randomize;
    if (randomize == UDM1_RANDOMIZE_SCREEN) desc.screen_spp = spp;
    if (desc.dimensions < 2) {
        *error = "udm1 preset '" + preset + "' has fewer than the 2 dimensions a pixel sample needs";
        return nullptr;
    }
    udm1_seq *seq = nullptr;
    if (udm1_seq_create_desc(&desc, &seq) != UDM1_OK) {
        *error = udm1_last_error();
        return nullptr;
    }
    return SharedSeq(seq, SeqDeleter());
}

// The sequence of a scene's Sampler "udm1", from its parameters as pbrt-v4's scene parser gives them:
// "string preset", "string randomization", "integer seed", "integer pixelsamples" (the last two 32-bit
// in pbrt, taken here as long long so that nothing is narrowed before it is checked). On failure
// returns null and sets *error to one line naming the parameter (and the library's reason).
inline SharedSeq create_for_scene(const std::string &preset, const std::string &randomization, long long seed,
                                  long long pixelsamples, std::string *error)
{
    uint32_t randomize = 0;
    if (!randomization_from_name(randomization, &randomize)) {
        *error = "udm1 sampler: randomization '" + randomization +
                 "' is not one of default, none, shift, permute, owen, screen";
        return nullptr;
    }
    if (seed < 0 || seed > 0x7FFFFFFFLL) {
        *error = "udm1 sampler: seed " + std::to_string(seed) + " is not in [0, 2147483647]";
        return nullptr;
    }
    if (pixelsamples < 1 || pixelsamples > 0x7FFFFFFFLL) {
        *error = "udm1 sampler: pixelsamples " + std::to_string(pixelsamples) + " is not in [1, 2147483647]";
        return nullptr;
    }
    std::string why;
    SharedSeq seq = create_sequence(preset, randomize, (uint64_t)seed, (uint32_t)pixelsamples, &why);
    if (!seq)
        *error = "udm1 sampler: preset '" + preset + "' with randomization '" + randomization + "' and pixelsamples " +
                 std::to_string(pixelsamples) + " is refused: " + why;
    return seq;
}

// One thread's sampler over a shared sequence.
class PixelSampler {
public:
    explicit PixelSampler(SharedSeq seq) : seq_(std::move(seq)) {}
    PixelSampler(const PixelSampler &other) : seq_(other.seq_) {}  // a clone starts with no pixel
    PixelSampler &operator=(const PixelSampler &) = delete;

    const udm1_seq *sequence() const { return seq_.get(); }
    // The stream id of pixel (x, y).
    static uint64_t stream_of(int x, int y) { return ((uint64_t)(uint32_t)y << 32) | (uint32_t)x; }

    void start(int x, int y, int sample_index, int dimension)
    {
        uint64_t id = stream_of(x, y);
        if (!has_pixel_ || id != stream_.stream) {
            // a count of 64 never fails for a valid sequence (first dimension 0)
            udm1_stream_init(&stream_, seq_.get(), id, 0, UDM1_STREAM_DIMS);
            has_pixel_ = true;
        }
        index_ = (uint64_t)(uint32_t)sample_index;
        dimension_ = dimension > 2 ? (uint32_t)dimension : 2u;
    }
    template <class Float> Float get1d()
    {
        Float u;
        draw(dimension_, 1, &u);
        dimension_ += 1;
        return u;
    }
    template <class Float> void get2d(Float u[2])
    {
        draw(dimension_, 2, u);
        dimension_ += 2;
    }
    template <class Float> void pixel2d(Float u[2]) { draw(0, 2, u); }

    uint64_t index() const { return index_; }
    uint32_t dimension() const { return dimension_; }

private:
    void draw(uint32_t dim, uint32_t n, float *out) const { udm1_stream_draw_f32(&stream_, index_, dim, n, out); }
    void draw(uint32_t dim, uint32_t n, double *out) const { udm1_stream_draw_f64(&stream_, index_, dim, n, out); }

    SharedSeq seq_;
    udm1_stream stream_{};
    bool has_pixel_ = false;
    uint64_t index_ = 0;
    uint32_t dimension_ = 2;
};

}  // namespace udm1pbrt
