// udm1-ao - ambient occlusion with any udm1 sampler on Embree (paper, section 4.2).
//
//   udm1-ao [options] [-o ao.exr] [--png ao.png]       render (default: built-in Cornell box, episwr, 64 spp)
//   udm1-ao reference -o ref.exr [options]             a high-spp reference (default sobol-owen, 8192 spp),
//                                                      rendered only if ref.exr was not made by the same settings
//   udm1-ao compare IMAGE REFERENCE [--diff diff.png]   MSE, RMSE, PSNR (peak 1, linear values)
//   udm1-ao sweep --against REF.exr --samplers a,b --spps 16,64 [--seeds N] [--images DIR] [options]
//                                                      many renders in one process, one CSV line each
//
// Errors are one line, "udm1-ao: ...", exit 2 for bad arguments and 1 for
// failures (an unreadable scene names its file and line); outputs are written
// under temporary names and renamed, so a failure leaves no partial image.
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"
#include "udm1app/image_read.h"
#include "udm1app/image_write.h"
#include "udm1app/partial_image.h"
#include "ao_render.h"
#include "embree_scene.h"
#include "scene.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <memory>
#include <string>
#include <vector>

using udm1app::Error;

namespace {

const char *USAGE =
    "usage: udm1-ao [options] [-o IMAGE.exr|.png] [--png IMAGE.png]   (neither: writes ao.png)\n"
    "       udm1-ao reference -o REF.exr [options]   (defaults: --sampler sobol-owen --spp 8192; reuses REF.exr\n"
    "                                                if the same scene and settings made it)\n"
    "       udm1-ao merge A.exr B.exr ... -o OUT.exr [--png OUT.png]   (sample ranges and tiles of one render)\n"
    "       udm1-ao compare IMAGE REFERENCE [--diff DIFF.png]\n"
    "       udm1-ao sweep --against REF.exr [--samplers A,B,...|all] [--spps N,M,...] [--seeds K] [--images DIR]\n"
    "                     [options]: every sampler x spp x seed 1..K, one CSV line each (sampler,spp,seed,\n"
    "                     seconds,rays,rmse,psnr) against REF.exr; DIR gets seed 1's images as SAMPLER-SPPspp.png\n"
    "options:\n"
    "  --scene S       a .pbrt, .ply or .obj file, or builtin:cornell|plane|box|wall (default builtin:cornell)\n"
    "  --sampler S     any udm1 sampler with 2 dimensions (4 with --jitter); default episwr\n"
    "  --spp N         samples per pixel (default 64)      --seed S   sampler seed (default 1)\n"
    "  --spp-first F   render only sample indices [F, F + C) of the --spp N ... (-o IMAGE.exr keeps exact\n"
    "  --spp-count C   ... counts: merge joins ranges and tiles into the whole render, bit for bit)\n"
    "  --pixel-bounds X0,Y0,X1,Y1  render only the pixels [X0, X1) x [Y0, Y1) (a tile)\n"
    "  --randomize R   none|default|shift|permute|owen|screen (default: the sampler's default; screen:\n"
    "                  Weyl sets, blue-noise error across pixels)\n"
    "  --size WxH      image size (default: 256x256 for built-in scenes, else the scene's film)\n"
    "  --maxdist D     occlusion ray length (default: unbounded)\n"
    "  --jitter        jitter the primary ray too (4D: dims 0,1 pixel, 2,3 direction)\n"
    "  --method M      single|packet|stream: how occlusion rays go to Embree (default stream, the fastest)\n"
    "  --threads N     default: all cores\n"
    "prints one line: sampler, spp, seconds, rays per second.\n";

const uint64_t MAX_PIXELS = 1ull << 26;  // 8192 x 8192: 256 MiB of float pixels

struct Options {
    udm1ao::Options ao;
    std::string scene = "builtin:cornell", output, png, diff;
    std::vector<std::string> positional;
    uint32_t threads = 0;
    bool compare = false, reference = false, sweep = false, merge = false, size_given = false, sampler_given = false,
         spp_given = false;
    // sweep
    std::string against, images;
    std::vector<std::string> samplers;
    std::vector<uint32_t> spps;
    uint32_t seeds = 1;
};

Options parse(int argc, char **argv)
{
    Options o;
    std::vector<std::string> args(argv + 1, argv + argc);
    size_t i = 0;
    if (!args.empty() && (args[0] == "help" || args[0] == "--help")) {
        std::fputs(USAGE, stdout);
        std::exit(0);
    }
    if (!args.empty() && args[0] == "compare") o.compare = true, i = 1;
    if (!args.empty() && args[0] == "reference") o.reference = true, i = 1;
    if (!args.empty() && args[0] == "sweep") o.sweep = true, i = 1;
    if (!args.empty() && args[0] == "merge") o.merge = true, i = 1;
    auto sweep_only = [&](const std::string &flag) {
        if (!o.sweep) throw Error(flag + " is an option of udm1-ao sweep");
    };
    auto value = [&](const std::string &flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + " needs a value");
        return args[++i];
    };
    for (; i < args.size(); ++i) {
        const std::string &a = args[i];
        if (a == "--scene") o.scene = value(a);
        else if (a == "--sampler") o.ao.sampler = value(a), o.sampler_given = true;
        else if (a == "--spp") o.ao.spp = (uint32_t)udm1app::parse_u64(value(a), "--spp", 1, 1u << 20), o.spp_given = true;
        else if (a == "--spp-first") o.ao.first = (uint32_t)udm1app::parse_u64(value(a), a, 0, (1u << 20) - 1);
        else if (a == "--spp-count") o.ao.count = (uint32_t)udm1app::parse_u64(value(a), a, 1, 1u << 20);
        else if (a == "--pixel-bounds") udm1app::parse_pixel_bounds(value(a), a, o.ao.bounds);
        else if (a == "--seed") o.ao.seed = udm1app::parse_u64(value(a), "--seed", 0, UINT64_MAX);
        else if (a == "--randomize") o.ao.randomize = udm1app::parse_randomize(value(a));
        else if (a == "--size") {
            udm1app::parse_size(value(a), a, 16384, MAX_PIXELS, &o.ao.width, &o.ao.height);
            o.size_given = true;
        } else if (a == "--maxdist") o.ao.max_distance = udm1app::parse_double(value(a), "--maxdist", 1e-12, 1e300);
        else if (a == "--jitter") o.ao.jitter = true;
        else if (a == "--method") {
            std::string m = value(a);
            if (m == "single") o.ao.method = udm1ao::Method::Single;
            else if (m == "packet") o.ao.method = udm1ao::Method::Packet;
            else if (m == "stream") o.ao.method = udm1ao::Method::Stream;
            else throw Error("--method '" + m + "' is not single, packet or stream");
        } else if (a == "--threads") o.threads = (uint32_t)udm1app::parse_u64(value(a), "--threads", 1, 1024);
        else if (a == "--against") sweep_only(a), o.against = value(a);
        else if (a == "--images") sweep_only(a), o.images = value(a);
        else if (a == "--samplers") sweep_only(a), o.samplers = udm1app::parse_list(value(a), a);
        else if (a == "--spps") {
            sweep_only(a);
            for (const std::string &n : udm1app::parse_list(value(a), a)) o.spps.push_back((uint32_t)udm1app::parse_u64(n, a, 1, 1u << 20));
        } else if (a == "--seeds") sweep_only(a), o.seeds = (uint32_t)udm1app::parse_u64(value(a), a, 1, 100000);
        else if (a == "-o") o.output = value(a);
        else if (a == "--png") o.png = value(a);
        else if (a == "--diff") o.diff = value(a);
        else if (!a.empty() && a[0] == '-') throw Error("unknown option '" + a + "'");
        else o.positional.push_back(a);
    }
    if (o.compare && o.positional.size() != 2) throw Error("compare needs IMAGE and REFERENCE");
    if (!o.compare && !o.merge && !o.positional.empty()) throw Error("unexpected argument '" + o.positional[0] + "'");
    if (o.merge && o.positional.empty()) throw Error("merge needs the images to merge");
    if (o.merge && o.output.empty()) throw Error("merge needs -o OUT.exr");
    const bool part = o.ao.first || o.ao.count || o.ao.bounds[2];
    if (part && (o.sweep || o.reference))
        throw Error(std::string(o.sweep ? "sweep" : "reference") + " renders every sample and pixel: no --spp-first/--spp-count/--pixel-bounds");
    if (o.ao.first >= o.ao.spp) throw Error("--spp-first " + std::to_string(o.ao.first) + " is not below --spp " + std::to_string(o.ao.spp));
    if (o.ao.count && (uint64_t)o.ao.first + o.ao.count > o.ao.spp)
        throw Error("--spp-first + --spp-count (" + std::to_string((uint64_t)o.ao.first + o.ao.count) + ") exceeds --spp " +
                    std::to_string(o.ao.spp));
    if (o.sweep) {
        if (o.against.empty()) throw Error("sweep needs --against REF.exr");
        if (!o.output.empty() || !o.png.empty()) throw Error("sweep writes no -o/--png image (use --images DIR)");
        if (o.samplers.empty()) o.samplers = {o.ao.sampler};
        if (o.spps.empty()) o.spps = {o.ao.spp};
    }
    if (!o.compare && !o.reference && !o.sweep && !o.merge && o.output.empty() && o.png.empty()) o.png = "ao.png";
    if (o.reference) {
        if (o.output.empty()) throw Error("reference needs -o REF.exr");
        if (!o.sampler_given) o.ao.sampler = "sobol-owen";
        if (!o.spp_given) o.ao.spp = 8192;
    }
    return o;
}

std::vector<float> grey_to_rgb(const std::vector<float> &v)
{
    std::vector<float> rgb(v.size() * 3);
    for (size_t i = 0; i < v.size(); ++i) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = v[i];
    return rgb;
}

int run_merge(const Options &o)
{
    for (const std::string &path : {o.output, o.png})
        if (!path.empty()) udm1app::AtomicFile probe(path);
    if (!udm1app::is_exr_path(o.output)) throw Error("-o '" + o.output + "': merge writes OpenEXR (.exr)", 2);
    udm1app::PartialImage p = udm1app::merge_partials(o.positional);
    if (p.channels != std::vector<std::string>{"A"}) throw Error("'" + o.positional[0] + "' is not an udm1-ao image", 2);
    udm1app::write_partial(o.output, p);
    if (!o.png.empty())
        udm1app::write_image(o.png, p.rgb(), p.width, p.height, 3, false, 8, {{"udm1:render", p.made_by}});
    std::printf("merged %zu image(s): samples [%llu, %llu) of %llu, pixels [%d, %d) x [%d, %d)\n", o.positional.size(),
                (unsigned long long)p.first, (unsigned long long)(p.first + p.count), (unsigned long long)p.spp, p.x0,
                p.x0 + p.width, p.y0, p.y0 + p.height);
    return 0;
}

int run_compare(const Options &o)
{
    udm1app::LoadedImage a = udm1app::read_image(o.positional[0]), ref = udm1app::read_image(o.positional[1]);
    std::vector<float> diff;
    udm1app::Comparison c = udm1app::compare(a, ref, true, o.diff.empty() ? nullptr : &diff);
    std::printf("mse %.6g rmse %.6g psnr %.4f\n", c.mse, c.rmse, c.psnr);
    if (!o.diff.empty()) {
        for (float &v : diff) v = std::min(1.0f, 10.0f * v);  // ten times the difference
        udm1app::write_image(o.diff, grey_to_rgb(diff), a.width, a.height, 3, true);
    }
    return 0;
}

// What made an image, stored in its metadata: a reference is reused only if this string matches.
// The ray method and thread count are left out: they do not change the image (tested).
std::string description(const udm1scene::Scene &scene, const udm1ao::Options &a)
{
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "udm1-ao %s scene %016llx size %dx%d sampler %s spp %u seed %llu randomize %u maxdist %.17g jitter %d",
                  udm1_version_string(), (unsigned long long)scene.digest(), a.width, a.height, a.sampler.c_str(),
                  a.spp, (unsigned long long)a.seed, a.randomize, a.max_distance, (int)a.jitter);
    return buf;
}

int run_sweep(const Options &o, const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt)
{
    udm1app::LoadedImage ref = udm1app::read_image(o.against);
    if (ref.width != o.ao.width || ref.height != o.ao.height)
        throw Error("'" + o.against + "' is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                        ", the renders " + std::to_string(o.ao.width) + "x" + std::to_string(o.ao.height),
                    2);
    std::vector<std::string> samplers = o.samplers;
    if (samplers.size() == 1 && samplers[0] == "all") {
        samplers.clear();
        for (size_t k = 0; k < udm1_preset_count(); ++k) {
            udm1_preset_info info;
            if (udm1_preset_get(k, &info) == UDM1_OK && info.max_dimensions >= (o.ao.jitter ? 4u : 2u))
                samplers.push_back(info.name);
        }
    }
    for (const std::string &s : samplers) {  // every name before the first render
        udm1ao::Options a = o.ao;
        a.sampler = s;
        udm1_seq_destroy(udm1ao::make_sampler(a));
    }
    if (!o.images.empty() && (!std::filesystem::is_directory(o.images) || access(o.images.c_str(), W_OK) != 0))
        throw Error("--images '" + o.images + "' is not a writable folder", 1);
    std::printf("sampler,spp,seed,seconds,rays,rmse,psnr\n");
    for (const std::string &s : samplers)
        for (uint32_t spp : o.spps)
            for (uint32_t seed = 1; seed <= o.seeds; ++seed) {
                udm1ao::Options a = o.ao;
                a.sampler = s, a.spp = spp, a.seed = seed;
                udm1ao::Stats st;
                udm1ao::Image img;
                try {
                    img = udm1ao::render(scene, rt, a, &st);
                } catch (const std::runtime_error &e) {
                    throw Error(e.what(), 2);
                }
                udm1app::LoadedImage mine;
                mine.width = img.width, mine.height = img.height, mine.channels = 1, mine.pixels = img.values;
                udm1app::Comparison c = udm1app::compare(mine, ref, true, nullptr);
                std::printf("%s,%u,%u,%.6f,%llu,%.8g,%.6f\n", s.c_str(), spp, seed, st.seconds,
                            (unsigned long long)st.rays, c.rmse, c.psnr);
                std::fflush(stdout);
                if (!o.images.empty() && seed == 1)
                    udm1app::write_image(o.images + "/" + s + "-" + std::to_string(spp) + "spp.png",
                                         grey_to_rgb(img.values), img.width, img.height, 3, false, 8,
                                         {{"udm1:render", description(scene, a)}});
            }
    return 0;
}

int run_render(Options o)
{
    udm1scene::Scene scene;
    try {
        scene = udm1scene::load_scene(o.scene, udm1scene::Need::Geometry);
    } catch (const udm1scene::SceneError &e) {
        throw Error(e.what(), 1);
    }
    if (!scene.ignored.empty())  // one line: what ambient occlusion does not need
        std::fprintf(stderr, "udm1-ao: note: %zu kind(s) of appearance left out, first %s\n", scene.ignored.size(),
                     scene.ignored[0].c_str());
    for (const std::string &n : scene.notes) std::fprintf(stderr, "udm1-ao: note: %s\n", n.c_str());
    if (!o.size_given && scene.source.rfind("builtin:", 0) == 0) o.ao.width = o.ao.height = 256;
    if ((o.ao.first || o.ao.count || o.ao.bounds[2]) && !o.output.empty() && !udm1app::is_exr_path(o.output))
        throw Error("-o '" + o.output + "': a sample range or tile is written as OpenEXR (.exr), whose counts merge", 2);
    // check the outputs' folders before rendering: a bad path fails at once
    for (const std::string &path : {o.output, o.png})
        if (!path.empty()) udm1app::AtomicFile probe(path);
    if (o.ao.width == 0) o.ao.width = scene.width, o.ao.height = scene.height;
    if ((uint64_t)o.ao.width * o.ao.height > MAX_PIXELS)
        throw Error(o.scene + ": the film (" + std::to_string(o.ao.width) + "x" + std::to_string(o.ao.height) +
                    ") has more than " + std::to_string(MAX_PIXELS) + " pixels; pass --size", 2);
    const std::string made_by = description(scene, o.ao);
    if (o.reference) {
        std::FILE *f = std::fopen(o.output.c_str(), "rb");
        if (f) {
            std::fclose(f);
            try {
                udm1app::LoadedImage old = udm1app::read_image(o.output);
                if (old.attributes["udm1:render"] == made_by) {
                    std::printf("reference %s reused (%s)\n", o.output.c_str(), made_by.c_str());
                    if (!o.png.empty()) {
                        std::vector<float> grey((size_t)old.width * old.height);
                        for (size_t i = 0; i < grey.size(); ++i) grey[i] = old.pixels[i * old.channels];
                        udm1app::write_image(o.png, grey_to_rgb(grey), old.width, old.height, 3, false, 8,
                                             {{"udm1:render", made_by}});
                        std::printf("wrote %s\n", o.png.c_str());
                    }
                    return 0;
                }
            } catch (const Error &) {  // unreadable: render it again
            }
        }
    }
    udm1scene::EmbreeScene rt(scene);
    if (o.sweep) return run_sweep(o, scene, rt);
    udm1ao::Stats stats;
    udm1ao::Image img;
    try {
        img = udm1ao::render(scene, rt, o.ao, &stats);
    } catch (const std::runtime_error &e) {
        throw Error(e.what(), 2);
    }
    const std::vector<std::pair<std::string, std::string>> meta = {{"udm1:render", made_by}};
    img.sums.made_by = made_by;
    if (!o.output.empty()) {
        if (udm1app::is_exr_path(o.output)) udm1app::write_partial(o.output, img.sums);  // exact counts: ranges and tiles merge
        else udm1app::write_image(o.output, grey_to_rgb(img.values), img.width, img.height, 3, false, 8, meta);
    }
    if (!o.png.empty()) udm1app::write_image(o.png, grey_to_rgb(img.values), img.width, img.height, 3, false, 8, meta);
    std::printf("sampler %s spp %u samples [%llu, %llu) size %dx%d image %dx%d at %d,%d seconds %.4f rays %llu "
                "rays_per_second %.4g\n",
                o.ao.sampler.c_str(), o.ao.spp, (unsigned long long)img.sums.first, (unsigned long long)(img.sums.first + img.sums.count),
                img.width, img.height, img.sums.full_width, img.sums.full_height, img.sums.x0, img.sums.y0, stats.seconds, (unsigned long long)stats.rays, stats.rays / std::max(stats.seconds, 1e-9));
    for (const std::string &path : {o.output, o.png})
        if (!path.empty()) std::printf("wrote %s\n", path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    return udm1app::run_tool("udm1-ao", [&] {
        Options o = parse(argc, argv);
        std::unique_ptr<tbb::global_control> limit;
        if (o.threads) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        return o.compare ? run_compare(o) : o.merge ? run_merge(o) : run_render(o);
    });
}
