// renderer.h - the front end udm1-ao and udm1-pt share: one command line (the same spellings for the
// same things), the subcommands written once, and a small interface each renderer implements.
//
//   TOOL [options] [-o IMAGE.exr] [--png IMAGE.png]        render (neither output: writes TOOL's PNG)
//   TOOL reference -o REF.exr [options]                    high spp; reused if REF.exr was made by the
//                                                          same scene and settings
//   TOOL merge A.exr B.exr ... -o OUT.exr [--png P]        add sample ranges and tiles of one render
//   TOOL compare IMAGE REFERENCE [--diff D.png] [--exact]  MSE, RMSE, PSNR; --exact: identical values?
//   TOOL sweep --against REF.exr [--samplers ..] [--spps ..] [--seeds K] [--images DIR] [options]
//
// A renderer describes what makes its image and renders a sample range of a tile into a partial
// image (udm1app/partial_image.h); everything else is here.
#pragma once

#include "udm1app/cli.h"
#include "udm1app/partial_image.h"

#include <udm1/seq.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace udm1app {

// The options every renderer shares, parsed here.
struct RenderSettings {
    std::string command = "render";  // render, reference, merge, compare, sweep, or a renderer's own
    std::string scene = "builtin:cornell", sampler, output, png, diff, against, images;
    std::vector<std::string> positional, samplers;
    std::vector<uint32_t> spps;
    uint32_t spp = 0, seeds = 1, threads = 0;
    uint32_t randomize = UDM1_RANDOMIZE_DEFAULT;
    uint64_t seed = 1, first = 0, count = 0;  // count 0: up to spp
    uint64_t frame = 0;                        // an animation's frame: its own seed (frame_seed)
    std::string checkpoints;                   // render: "K1,K2,..." or "every": prefix images [0, K)
    int bounds[4] = {0, 0, 0, 0};              // all zero: every pixel
    int width = 0, height = 0;                 // 0: the renderer's default for the scene
    bool size_given = false, sampler_given = false, spp_given = false, exact = false;
    bool exr_zip = true;                       // --exr-compression: the images with exact sums zip-compressed

    bool part() const { return first || count || bounds[2]; }  // a sample range or a tile
};

// What a sweep's render reports: its CSV columns after sampler,spp,seed.
struct RenderStats {
    double seconds = 0;
    std::vector<std::pair<std::string, std::string>> columns;  // (name, value) before rmse,psnr
    std::vector<std::pair<std::string, std::string>> after;    // after rmse,psnr
};

class Renderer {
public:
    struct Defaults {
        const char *tool;              // "udm1-ao"
        const char *usage;             // the whole --help text
        const char *default_png;       // written when a render names no output
        const char *sampler;           // the render's default sampler
        uint32_t spp;                  // ... and spp
        const char *reference_sampler; // reference's defaults
        uint32_t reference_spp;
        uint32_t max_spp;
        std::vector<std::string> commands;  // the renderer's own subcommands (udm1-pt: export)
    };
    virtual ~Renderer() = default;
    virtual const Defaults &defaults() const = 0;
    // A renderer's own option: read it (value() returns its argument) and return true; false if not its.
    virtual bool option(const std::string &flag, const std::function<std::string()> &value, RenderSettings &s) = 0;
    // Load the scene of s (notes to stderr) and settle what depends on it (size, spp); bad input throws
    // Error. Called once, before any render.
    virtual void load(RenderSettings &s) = 0;
    // What makes the image, without its sample range and window: a reference is reused only if it matches.
    virtual std::string describe(const RenderSettings &s) const = 0;
    // Render s's sample range of its tile (made_by set); stats for a sweep's line.
    virtual PartialImage render(const RenderSettings &s, RenderStats *stats) = 0;
    // The line a render prints after rendering (what it did, how fast).
    virtual void report(const RenderSettings &s, const PartialImage &image, const RenderStats &stats) = 0;
    // A partial image's mean as the RGB a PNG shows, and whether it is sRGB-encoded.
    virtual std::vector<float> display(const PartialImage &image, bool *srgb) const = 0;
    // Whether an image to merge is one of this renderer's (its summed channels).
    virtual bool owns(const PartialImage &image) const = 0;
    // Whether a sampler can render here (the sweep checks every name before its first render); throws Error.
    virtual void check_sampler(const std::string &name) const = 0;
    // Whether -o may name a format other than OpenEXR for a whole render (an 8-bit picture).
    virtual bool pictures_as_output() const { return false; }
    // A renderer's own subcommand (Defaults::commands), after load.
    virtual int run_command(const RenderSettings &s) { (void)s; return 2; }
};

// The sampler seed of an animation's frame: the seed itself for frame 0, else seed + frame * 2^64 / phi
// (mod 2^64): each frame an independent randomization of the same scheme, so that consecutive frames'
// errors are uncorrelated while each frame keeps its screen-space structure.
inline uint64_t frame_seed(uint64_t seed, uint64_t frame) { return seed + frame * 0x9E3779B97F4A7C15ull; }

// A renderer's own options with the shared settings of s applied (its Options type has the fields
// sampler, spp, seed, randomize, first, count, bounds, width and height).
template <class Options> Options with_settings(Options o, const RenderSettings &s)
{
    o.sampler = s.sampler, o.spp = s.spp, o.seed = frame_seed(s.seed, s.frame), o.randomize = s.randomize;
    o.first = static_cast<decltype(o.first)>(s.first), o.count = static_cast<decltype(o.count)>(s.count);
    for (int k = 0; k < 4; ++k) o.bounds[k] = s.bounds[k];
    o.width = s.width, o.height = s.height;
    return o;
}

// The largest image the renderers make: 8192 x 8192 (256 MiB of floats per channel).
constexpr uint64_t MAX_RENDER_PIXELS = 1ull << 26;

// Parse the command line, run the subcommand, return the exit code (errors as Error, see cli.h).
int run_renderer(Renderer &renderer, int argc, char **argv);

// A renderer app's main: its one-line errors and exit codes (cli.h) around run_renderer.
template <class R> int renderer_main(int argc, char **argv)
{
    R renderer;
    return run_tool(renderer.defaults().tool, [&] { return run_renderer(renderer, argc, argv); });
}

// Check --spp-first and --spp-count against --spp; throws Error.
void check_sample_range(const RenderSettings &s);

// The presets a sweep's "--samplers all" means: every preset with at least `dims` dimensions.
std::vector<std::string> presets_with_dimensions(uint32_t dims);

}  // namespace udm1app
