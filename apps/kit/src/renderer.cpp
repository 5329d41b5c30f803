// renderer.cpp - the renderers' shared command line and subcommands (renderer.h).
#include "udm1app/renderer.h"

#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"
#include "udm1app/image_read.h"
#include "udm1app/image_write.h"

#include <udm1/udm1.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <unistd.h>

namespace udm1app {

namespace {

bool is_command(const Renderer::Defaults &d, const std::string &word)
{
    static const char *const SHARED[] = {"reference", "merge", "compare", "sweep"};
    for (const char *c : SHARED)
        if (word == c) return true;
    return std::find(d.commands.begin(), d.commands.end(), word) != d.commands.end();
}

RenderSettings parse(Renderer &r, int argc, char **argv)
{
    const Renderer::Defaults &d = r.defaults();
    const std::string tool = d.tool;
    RenderSettings s;
    s.sampler = d.sampler;
    s.spp = d.spp;
    std::vector<std::string> args(argv + 1, argv + argc);
    size_t i = 0;
    if (!args.empty() && (args[0] == "help" || args[0] == "--help")) {
        std::fputs(d.usage, stdout);
        std::exit(0);
    }
    if (!args.empty() && is_command(d, args[0])) s.command = args[0], i = 1;
    if (i < args.size() && (args[i] == "--help" || args[i] == "help")) {  // TOOL SUBCOMMAND --help
        std::fputs(d.usage, stdout);
        std::exit(0);
    }
    auto value = [&](const std::string &flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + " needs a value");
        return args[++i];
    };
    auto only = [&](const char *command, const std::string &flag) {
        if (s.command != command) throw Error(flag + " is an option of " + tool + " " + command);
    };
    for (; i < args.size(); ++i) {
        const std::string &a = args[i];
        if (a == "--scene") s.scene = value(a);
        else if (a == "--sampler") s.sampler = value(a), s.sampler_given = true;
        else if (a == "--spp") s.spp = (uint32_t)parse_u64(value(a), a, 1, d.max_spp), s.spp_given = true;
        else if (a == "--spp-first") s.first = parse_u64(value(a), a, 0, d.max_spp - 1);
        else if (a == "--spp-count") s.count = parse_u64(value(a), a, 1, d.max_spp);
        else if (a == "--pixel-bounds") parse_pixel_bounds(value(a), a, s.bounds);
        else if (a == "--seed") s.seed = parse_u64(value(a), a, 0, UINT64_MAX);
        else if (a == "--frame") s.frame = parse_u64(value(a), a, 0, UINT32_MAX);
        else if (a == "--checkpoints") only("render", a), s.checkpoints = value(a);
        else if (a == "--exr-compression") s.exr_zip = parse_exr_compression(value(a));
        else if (a == "--randomize") s.randomize = parse_randomize(value(a));
        else if (a == "--size") {
            parse_size(value(a), a, 16384, MAX_RENDER_PIXELS, &s.width, &s.height);
            s.size_given = true;
        } else if (a == "--threads") s.threads = (uint32_t)parse_u64(value(a), a, 1, 1024);
        else if (a == "-o") s.output = value(a);
        else if (a == "--png") s.png = value(a);
        else if (a == "--diff") s.diff = value(a);
        else if (a == "--exact") only("compare", a), s.exact = true;
        else if (a == "--against") only("sweep", a), s.against = value(a);
        else if (a == "--images") only("sweep", a), s.images = value(a);
        else if (a == "--samplers") only("sweep", a), s.samplers = parse_list(value(a), a);
        else if (a == "--spps") {
            only("sweep", a);
            for (const std::string &n : parse_list(value(a), a)) s.spps.push_back((uint32_t)parse_u64(n, a, 1, d.max_spp));
        } else if (a == "--seeds") only("sweep", a), s.seeds = (uint32_t)parse_u64(value(a), a, 1, 100000);
        else if (r.option(a, [&] { return value(a); }, s)) continue;
        else if (!a.empty() && a[0] == '-') throw Error("unknown option '" + quote_raw(a) + "'");
        else s.positional.push_back(a);
    }
    const bool own = std::find(d.commands.begin(), d.commands.end(), s.command) != d.commands.end();
    if (s.command == "compare" && s.positional.size() != 2) throw Error("compare needs IMAGE and REFERENCE");
    if (s.command == "merge" && s.positional.empty()) throw Error("merge needs the images to merge");
    if (s.command != "compare" && s.command != "merge" && !own && !s.positional.empty())
        throw Error("unexpected argument '" + quote_raw(s.positional[0], 80) + "'");
    if (s.command == "merge" && s.output.empty()) throw Error("merge needs -o OUT.exr");
    if (s.command == "reference") {
        if (s.output.empty()) throw Error("reference needs -o REF.exr");
        if (!s.sampler_given) s.sampler = d.reference_sampler;
        if (!s.spp_given) s.spp = d.reference_spp;
    }
    if ((s.command == "reference" || s.command == "sweep") && s.part())
        throw Error(s.command + " renders every sample and pixel: no --spp-first/--spp-count/--pixel-bounds");
    if (s.command == "sweep") {
        if (s.against.empty()) throw Error("sweep needs --against REF.exr");
        if (!s.output.empty() || !s.png.empty()) throw Error("sweep writes no -o/--png image (use --images DIR)");
        if (s.samplers.empty()) s.samplers = {s.sampler};
        if (s.spps.empty()) s.spps = {s.spp};
    }
    if (s.command == "render" && s.output.empty() && s.png.empty()) s.png = d.default_png;
    if (s.spp_given || s.command != "render") check_sample_range(s);  // else after load (the scene's spp)
    return s;
}

void write_display(const Renderer &r, AtomicFile &file, const PartialImage &image)
{
    bool srgb = false;
    std::vector<float> rgb = r.display(image, &srgb);
    write_image(file, rgb, image.width, image.height, 3, srgb, 8, {{"udm1:render", image.made_by}});
}

// The run's output files, created at once (a path that cannot be written fails before any work); the
// empty paths left out.
std::vector<AtomicFile> open_outputs(std::initializer_list<std::string> paths)
{
    std::vector<AtomicFile> files;
    for (const std::string &path : paths)
        if (!path.empty()) files.emplace_back(path);
    return files;
}

int run_compare(const RenderSettings &s)
{
    std::vector<AtomicFile> diff_file = open_outputs({s.diff});
    LoadedImage a = read_image(s.positional[0]), ref = read_image(s.positional[1]);
    std::vector<float> diff;
    Comparison c = compare(a, ref, true, s.diff.empty() ? nullptr : &diff);
    if (!s.diff.empty()) {  // ten times the difference, grey; written before anything is printed
        std::vector<float> rgb(diff.size() * 3);
        for (size_t i = 0; i < diff.size(); ++i) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = std::min(1.0f, 10.0f * diff[i]);
        write_image(diff_file[0], rgb, a.width, a.height, 3, true);
        commit_all(diff_file);
    }
    std::printf("mse %.6g rmse %.6g psnr %.4f\n", c.mse, c.rmse, c.psnr);
    if (s.exact) {  // every value of every channel, unclamped, bit for bit (the metadata may differ)
        size_t differ = 0;
        double largest = 0;
        if (a.channels != ref.channels) {
            std::printf("different: %d channels and %d\n", a.channels, ref.channels);
            return 0;
        }
        for (size_t i = 0; i < a.pixels.size(); ++i)
            if (std::memcmp(&a.pixels[i], &ref.pixels[i], sizeof(float)) != 0) {
                ++differ;
                largest = std::max(largest, (double)std::fabs(a.pixels[i] - ref.pixels[i]));
            }
        if (differ) std::printf("different: %zu of %zu values, largest difference %.6g\n", differ, a.pixels.size(), largest);
        else std::printf("identical: %zu values bit for bit\n", a.pixels.size());
    }
    return 0;
}

int run_merge(const Renderer &r, const RenderSettings &s)
{
    if (!is_exr_path(s.output)) throw Error("-o '" + s.output + "': merge writes OpenEXR (.exr)", 2);
    std::vector<AtomicFile> files = open_outputs({s.output, s.png});
    PartialImage p = merge_partials(s.positional);
    if (!r.owns(p)) throw Error("'" + s.positional[0] + "' is not an " + r.defaults().tool + " image", 2);
    write_partial(files[0], p, s.exr_zip);
    if (!s.png.empty()) write_display(r, files[1], p);
    commit_all(files);
    std::printf("merged %zu image(s): samples [%llu, %llu) of %llu, pixels [%d, %d) x [%d, %d)\n", s.positional.size(),
                (unsigned long long)p.first, (unsigned long long)(p.first + p.count), (unsigned long long)p.spp, p.x0,
                p.x0 + p.width, p.y0, p.y0 + p.height);
    return 0;
}

int run_sweep(Renderer &r, const RenderSettings &s)
{
    LoadedImage ref = read_image(s.against);
    if (ref.width != s.width || ref.height != s.height)
        throw Error("'" + s.against + "' is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                        ", the renders " + std::to_string(s.width) + "x" + std::to_string(s.height),
                    2);
    const bool all = s.samplers.size() == 1 && s.samplers[0] == "all";
    std::vector<std::string> usable;
    for (const std::string &name : all ? presets_with_dimensions(2) : s.samplers) {  // every name before rendering
        try {
            r.check_sampler(name);
        } catch (const Error &) {
            if (!all) throw;
            continue;  // "all": the presets this renderer can use
        }
        usable.push_back(name);
    }
    if (!s.images.empty() && (!std::filesystem::is_directory(s.images) || access(s.images.c_str(), W_OK) != 0))
        throw Error("--images '" + s.images + "' is not a writable folder", 1);
    bool header = false;
    std::vector<AtomicFile> images;  // committed together after the last render: an error leaves none
    for (const std::string &name : usable)
        for (uint32_t spp : s.spps)
            for (uint32_t seed = 1; seed <= s.seeds; ++seed) {
                RenderSettings one = s;
                one.sampler = name, one.spp = spp, one.seed = seed;
                RenderStats st;
                PartialImage img = r.render(one, &st);
                LoadedImage mine;
                mine.width = img.width, mine.height = img.height, mine.channels = (int)img.shown();
                mine.pixels = img.mean();
                Comparison c = compare(mine, ref, true, nullptr);
                if (!header) {
                    std::printf("sampler,spp,seed,seconds");
                    for (const auto &col : st.columns) std::printf(",%s", col.first.c_str());
                    std::printf(",rmse,psnr");
                    for (const auto &col : st.after) std::printf(",%s", col.first.c_str());
                    std::printf("\n");
                    header = true;
                }
                std::printf("%s,%u,%u,%.6f", name.c_str(), spp, seed, st.seconds);
                for (const auto &col : st.columns) std::printf(",%s", col.second.c_str());
                std::printf(",%.8g,%.6f", c.rmse, c.psnr);
                for (const auto &col : st.after) std::printf(",%s", col.second.c_str());
                std::printf("\n");
                std::fflush(stdout);
                if (!s.images.empty() && seed == 1) {
                    images.emplace_back(s.images + "/" + name + "-" + std::to_string(spp) + "spp.png");
                    write_display(r, images.back(), img);
                    images.back().finish();
                }
            }
    commit_all(images);
    return 0;
}

// A reference is reused when the file is a whole render of the same description.
bool reuse_reference(const Renderer &r, const RenderSettings &s, const std::string &made_by)
{
    if (access(s.output.c_str(), F_OK) != 0) return false;
    PartialImage old;
    try {
        old = read_partial(s.output);
    } catch (const Error &) {  // not a reference of ours: render it again
        return false;
    }
    if (old.made_by != made_by || old.first != 0 || old.count != old.spp || !old.whole()) return false;
    if (!s.png.empty()) {
        std::vector<AtomicFile> png = open_outputs({s.png});
        write_display(r, png[0], old);
        commit_all(png);
    }
    std::printf("reference %s reused (%s)\n", s.output.c_str(), made_by.c_str());
    if (!s.png.empty()) std::printf("wrote %s\n", s.png.c_str());
    return true;
}

// "K1,K2,..." (ascending, in 1..spp) or "every" (1..spp) as sample counts; throws Error.
std::vector<uint64_t> parse_checkpoints(const RenderSettings &s)
{
    std::vector<uint64_t> ks;
    if (s.checkpoints == "every") {
        for (uint64_t k = 1; k <= s.spp; ++k) ks.push_back(k);
        return ks;
    }
    for (const std::string &item : parse_list(s.checkpoints, "--checkpoints")) {
        ks.push_back(parse_u64(item, "--checkpoints", 1, s.spp));
        if (ks.size() > 1 && ks.back() <= ks[ks.size() - 2])
            throw Error("--checkpoints '" + s.checkpoints + "' is not ascending");
    }
    return ks;
}

// NAME.exr -> NAME.K.exr
std::string checkpoint_path(const std::string &output, uint64_t k)
{
    return output.substr(0, output.size() - 4) + "." + std::to_string(k) + output.substr(output.size() - 4);
}

// A render's prefixes: samples [0, K) of every pixel for each checkpoint K, each written as NAME.K.exr
// (exact sums: the prefix of a render equals the render of that range, bit for bit). The samples between
// checkpoints are rendered once.
int run_checkpoints(Renderer &r, const RenderSettings &s, const std::string &made_by)
{
    if (s.output.empty() || !is_exr_path(s.output)) throw Error("--checkpoints needs -o NAME.exr (it writes NAME.K.exr)", 2);
    if (s.part()) throw Error("--checkpoints renders from sample 0, every pixel: no --spp-first/--spp-count/--pixel-bounds", 2);
    const std::vector<uint64_t> ks = parse_checkpoints(s);
    PartialImage total;
    uint64_t done = 0;
    std::vector<AtomicFile> files;  // committed together after the last checkpoint: an error leaves none
    for (uint64_t k : ks) {
        RenderSettings slice = s;
        slice.first = done, slice.count = k - done;
        RenderStats stats;
        PartialImage part = r.render(slice, &stats);
        if (done == 0) {
            total = part;
        } else {
            for (size_t i = 0; i < total.sum.size(); ++i) total.sum[i] += part.sum[i];
            total.count += part.count, total.nonfinite += part.nonfinite, total.clamped += part.clamped;
        }
        total.made_by = made_by;
        files.emplace_back(checkpoint_path(s.output, k));
        write_partial(files.back(), total, s.exr_zip);
        files.back().finish();
        if (isatty(2))
            std::fprintf(stderr, "\r%s: %llu of %llu spp", r.defaults().tool, (unsigned long long)k,
                         (unsigned long long)ks.back());
        done = k;
    }
    if (isatty(2)) std::fprintf(stderr, "\n");
    commit_all(files);
    std::printf("wrote %zu checkpoints, %s .. %s\n", ks.size(), checkpoint_path(s.output, ks.front()).c_str(),
                checkpoint_path(s.output, ks.back()).c_str());
    return 0;
}

int run_render(Renderer &r, RenderSettings s)
{
    const Renderer::Defaults &d = r.defaults();
    r.load(s);
    if (!s.spp_given && s.command == "render") check_sample_range(s);
    if (s.width == 0 || s.height == 0) throw Error(s.scene + ": no image size; pass --size", 2);
    if ((uint64_t)s.width * s.height > MAX_RENDER_PIXELS)
        throw Error(s.scene + ": the film (" + std::to_string(s.width) + "x" + std::to_string(s.height) +
                        ") has more than " + std::to_string(MAX_RENDER_PIXELS) + " pixels; pass --size",
                    2);
    if (std::find(d.commands.begin(), d.commands.end(), s.command) != d.commands.end()) return r.run_command(s);
    const std::string made_by = r.describe(s);
    if (s.command == "reference" && reuse_reference(r, s, made_by)) return 0;
    if (!s.output.empty() && !is_exr_path(s.output)) {
        if (!r.pictures_as_output())
            throw Error("-o '" + s.output + "': " + d.tool + " writes OpenEXR (.exr); use --png for a PNG", 2);
        if (s.part())
            throw Error("-o '" + s.output + "': a sample range or tile is written as OpenEXR (.exr), whose counts merge", 2);
    }
    if (s.command == "sweep") return run_sweep(r, s);
    if (!s.checkpoints.empty()) {
        open_outputs({s.output, s.png});  // a bad output path fails before the render
        return run_checkpoints(r, s, made_by);
    }
    std::vector<AtomicFile> files = open_outputs({s.output, s.png});  // a bad path fails before the render
    RenderStats stats;
    PartialImage image = r.render(s, &stats);
    image.made_by = made_by;
    if (!s.output.empty()) {
        if (is_exr_path(s.output)) write_partial(files[0], image, s.exr_zip);  // exact sums: ranges and tiles merge
        else write_display(r, files[0], image);
    }
    if (!s.png.empty()) write_display(r, files.back(), image);
    commit_all(files);
    r.report(s, image, stats);
    for (const std::string &path : {s.output, s.png})
        if (!path.empty()) std::printf("wrote %s\n", path.c_str());
    return 0;
}

}  // namespace

void check_sample_range(const RenderSettings &s)
{
    if (s.first >= s.spp)
        throw Error("--spp-first " + std::to_string(s.first) + " is not below --spp " + std::to_string(s.spp));
    if (s.count && s.first + s.count > s.spp)
        throw Error("--spp-first + --spp-count (" + std::to_string(s.first + s.count) + ") exceeds --spp " +
                    std::to_string(s.spp));
}

std::vector<std::string> presets_with_dimensions(uint32_t dims)
{
    std::vector<std::string> names;
    for (size_t k = 0; k < udm1_preset_count(); ++k) {
        udm1_preset_info info;
        if (udm1_preset_get(k, &info) == UDM1_OK && info.max_dimensions >= dims) names.push_back(info.name);
    }
    return names;
}

int run_renderer(Renderer &renderer, int argc, char **argv)
{
    RenderSettings s = parse(renderer, argc, argv);
    std::unique_ptr<tbb::global_control> limit;
    if (s.threads) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, s.threads);
    if (s.command == "compare") return run_compare(s);
    if (s.command == "merge") return run_merge(renderer, s);
    return run_render(renderer, s);
}

}  // namespace udm1app
