// udm1-pt - an Embree path tracer in which the sampler is one switch (paper, section 5).
//
//   udm1-pt [options] [-o IMAGE.exr] [--png IMAGE.png]      render (default: built-in Cornell box)
//   udm1-pt reference -o REF.exr [options]                  high spp (default sobol-owen, 4096 spp); reused
//                                                           if REF.exr was made by the same scene and settings
//   udm1-pt merge A.exr B.exr ... -o OUT.exr [--png P]      add sample ranges of one render, exactly
//   udm1-pt compare IMAGE REFERENCE [--diff DIFF.png] [--exact]  MSE, RMSE, PSNR (peak 1 on clamped linear RGB);
//                                                           --exact: whether the values are identical
//   udm1-pt sweep --against REF.exr [--samplers ..] [--spps ..] [--seeds K] [--images DIR] [options]
//   udm1-pt export DIR [--scene S] [--size WxH]             the parsed scene as PLY files + scene.json
//
// Errors are one line, "udm1-pt: ...", exit 2 for bad arguments and 1 for failures (a bad scene
// names its file and line); images are written under temporary names and renamed, so a failure
// leaves no partial image.
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"
#include "udm1app/image_read.h"
#include "udm1app/image_write.h"
#include "embree_scene.h"
#include "integrator.h"
#include "scene_export.h"
#include "scene.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sys/resource.h>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

using udm1app::Error;

namespace {

const char *USAGE =
    "usage: udm1-pt [options] [-o IMAGE.exr] [--png IMAGE.png]   (neither: writes pt.png)\n"
    "       udm1-pt reference -o REF.exr [options]   (defaults: --sampler sobol-owen --spp 4096; reuses REF.exr\n"
    "                                                if the same scene and settings made it)\n"
    "       udm1-pt merge A.exr B.exr ... -o OUT.exr [--png OUT.png]   (sample ranges of one render)\n"
    "       udm1-pt compare IMAGE REFERENCE [--diff DIFF.png] [--exact]   (--exact: also whether every value is\n"
    "                                                   identical, unclamped, bit for bit)\n"
    "       udm1-pt sweep --against REF.exr [--samplers A,B,...] [--spps N,M,...] [--seeds K] [--images DIR]\n"
    "                     [options]: one CSV line per render (sampler,spp,seed,seconds,paths,rays,rmse,psnr,mean)\n"
    "       udm1-pt export DIR [--scene S] [--size WxH] [--maxdepth D]   (PLY files + scene.json, for Mitsuba)\n"
    "options:\n"
    "  --scene S         a .pbrt file or builtin:cornell|furnace (default builtin:cornell)\n"
    "  --sampler S       any udm1 sampler (udm1-seq list); default sobol-owen\n"
    "  --spp N           samples per pixel of the whole render (default 16)\n"
    "  --spp-first F     render only sample indices [F, F + C) of it ...\n"
    "  --spp-count C     ... (merge joins such ranges; the merged image equals the whole render)\n"
    "  --pixel-bounds X0,Y0,X1,Y1  render only the pixels [X0, X1) x [Y0, Y1) (a tile; merge joins tiles)\n"
    "  --seed S          sampler seed (default 1)   --randomize none|default|shift|permute|owen|screen\n"
    "  --size WxH        image size (default: 256x256 for built-in scenes, else the scene's film)\n"
    "  --maxdepth D      maximum bounces (default: the scene's, pbrt's 5)\n"
    "  --strategy S      mis|nee|bsdf: light found by both (MIS), light sampling, or BSDF sampling\n"
    "  --no-roulette     no Russian roulette\n"
    "  --rr-depth N      roulette from vertex N on (default 3; pbrt-v4's rule is 1)\n"
    "  --solid-angle S   near|always|never: triangle lights sampled by solid angle near the light (default),\n"
    "                    wherever possible (as pbrt-v4), or never (always by area)\n"
    "  --loop L          auto|scalar|wavefront: the path loop (default auto: wavefront where the scene is in its\n"
    "                    subset - triangles, diffuse, area lights, pinhole, MIS - else scalar)\n"
    "  --threads N       default: all cores\n";

const uint64_t MAX_PIXELS = 1ull << 26;

struct Options {
    udm1pt::Options pt;
    std::string command = "render", scene = "builtin:cornell", output, png, diff, against, images;
    std::vector<std::string> positional, samplers;
    std::vector<uint32_t> spps;
    uint32_t threads = 0, seeds = 1;
    bool size_given = false, sampler_given = false, spp_given = false, exact = false;
};

void check_sample_range(const Options &o)
{
    if (o.pt.first >= o.pt.spp) throw Error("--spp-first " + std::to_string(o.pt.first) + " is not below --spp " + std::to_string(o.pt.spp));
    if (o.pt.count && o.pt.first + o.pt.count > o.pt.spp)
        throw Error("--spp-first + --spp-count (" + std::to_string(o.pt.first + o.pt.count) + ") exceeds --spp " +
                    std::to_string(o.pt.spp));
}

Options parse(int argc, char **argv)
{
    Options o;
    std::vector<std::string> args(argv + 1, argv + argc);
    size_t i = 0;
    if (!args.empty() && (args[0] == "help" || args[0] == "--help")) {
        std::fputs(USAGE, stdout);
        std::exit(0);
    }
    if (!args.empty() && (args[0] == "reference" || args[0] == "merge" || args[0] == "compare" || args[0] == "sweep" ||
                          args[0] == "export"))
        o.command = args[0], i = 1;
    auto value = [&](const std::string &flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + " needs a value");
        return args[++i];
    };
    auto sweep_only = [&](const std::string &flag) {
        if (o.command != "sweep") throw Error(flag + " is an option of udm1-pt sweep");
    };
    for (; i < args.size(); ++i) {
        const std::string &a = args[i];
        if (a == "--scene") o.scene = value(a);
        else if (a == "--sampler") o.pt.sampler = value(a), o.sampler_given = true;
        else if (a == "--spp") o.pt.spp = (uint32_t)udm1app::parse_u64(value(a), a, 1, 1u << 24), o.spp_given = true;
        else if (a == "--spp-first") o.pt.first = udm1app::parse_u64(value(a), a, 0, (1u << 24) - 1);
        else if (a == "--spp-count") o.pt.count = udm1app::parse_u64(value(a), a, 1, 1u << 24);
        else if (a == "--pixel-bounds") udm1app::parse_pixel_bounds(value(a), a, o.pt.bounds);
        else if (a == "--seed") o.pt.seed = udm1app::parse_u64(value(a), a, 0, UINT64_MAX);
        else if (a == "--randomize") o.pt.randomize = udm1app::parse_randomize(value(a));
        else if (a == "--size") {
            udm1app::parse_size(value(a), a, 16384, MAX_PIXELS, &o.pt.width, &o.pt.height);
            o.size_given = true;
        } else if (a == "--maxdepth") o.pt.max_depth = (int)udm1app::parse_u64(value(a), a, 0, 1000);
        else if (a == "--strategy") {
            std::string s = value(a);
            if (s == "mis") o.pt.strategy = udm1pt::Strategy::Mis;
            else if (s == "nee") o.pt.strategy = udm1pt::Strategy::Nee;
            else if (s == "bsdf") o.pt.strategy = udm1pt::Strategy::Bsdf;
            else throw Error("--strategy '" + s + "' is not mis, nee or bsdf");
        } else if (a == "--no-roulette") o.pt.roulette = false;
        else if (a == "--loop") {
            std::string s = value(a);
            if (s == "auto") o.pt.loop = udm1pt::Loop::Auto;
            else if (s == "scalar") o.pt.loop = udm1pt::Loop::Scalar;
            else if (s == "wavefront") o.pt.loop = udm1pt::Loop::Wavefront;
            else throw Error("--loop '" + s + "' is not auto, scalar or wavefront");
        }
        else if (a == "--rr-depth") o.pt.rr_depth = (int)udm1app::parse_u64(value(a), a, 0, 1000);
        else if (a == "--solid-angle") {
            std::string s = value(a);
            if (s == "near") o.pt.near_light = udm1pt::Lights::NEAR_DEFAULT;
            else if (s == "always") o.pt.near_light = 0;
            else if (s == "never") o.pt.near_light = HUGE_VAL;
            else throw Error("--solid-angle '" + s + "' is not near, always or never");
        }
        else if (a == "--threads") o.threads = (uint32_t)udm1app::parse_u64(value(a), a, 1, 1024);
        else if (a == "-o") o.output = value(a);
        else if (a == "--png") o.png = value(a);
        else if (a == "--diff") o.diff = value(a);
        else if (a == "--exact") {
            if (o.command != "compare") throw Error("--exact is an option of udm1-pt compare");
            o.exact = true;
        }
        else if (a == "--against") sweep_only(a), o.against = value(a);
        else if (a == "--images") sweep_only(a), o.images = value(a);
        else if (a == "--samplers") sweep_only(a), o.samplers = udm1app::parse_list(value(a), a);
        else if (a == "--spps") {
            sweep_only(a);
            for (const std::string &n : udm1app::parse_list(value(a), a)) o.spps.push_back((uint32_t)udm1app::parse_u64(n, a, 1, 1u << 24));
        } else if (a == "--seeds") sweep_only(a), o.seeds = (uint32_t)udm1app::parse_u64(value(a), a, 1, 100000);
        else if (!a.empty() && a[0] == '-') throw Error("unknown option '" + a + "'");
        else o.positional.push_back(a);
    }
    if (o.command == "compare" && o.positional.size() != 2) throw Error("compare needs IMAGE and REFERENCE");
    if (o.command == "merge" && o.positional.empty()) throw Error("merge needs the images to merge");
    if (o.command == "export" && o.positional.size() != 1) throw Error("export needs one folder");
    if (o.command != "compare" && o.command != "merge" && o.command != "export" && !o.positional.empty())
        throw Error("unexpected argument '" + o.positional[0] + "'");
    if (o.command == "merge" && o.output.empty()) throw Error("merge needs -o OUT.exr");
    if (o.command == "reference") {
        if (o.output.empty()) throw Error("reference needs -o REF.exr");
        if (!o.sampler_given) o.pt.sampler = "sobol-owen";
        if (!o.spp_given) o.pt.spp = 4096;
        if (o.pt.first || o.pt.count || o.pt.bounds[2])
            throw Error("reference renders every sample and pixel: no --spp-first/--spp-count/--pixel-bounds");
    }
    if (o.command == "sweep") {
        if (o.against.empty()) throw Error("sweep needs --against REF.exr");
        if (o.pt.bounds[2]) throw Error("sweep renders whole images: no --pixel-bounds");
        if (!o.output.empty() || !o.png.empty()) throw Error("sweep writes no -o/--png image (use --images DIR)");
        if (o.samplers.empty()) o.samplers = {o.pt.sampler};
        if (o.spps.empty()) o.spps = {o.pt.spp};
    }
    if (o.command == "render" && o.output.empty() && o.png.empty()) o.png = "pt.png";
    if (o.spp_given || o.command != "render") check_sample_range(o);  // else once the scene's Sampler is read
    return o;
}

const char *strategy_name(udm1pt::Strategy s)
{
    return s == udm1pt::Strategy::Mis ? "mis" : s == udm1pt::Strategy::Nee ? "nee" : "bsdf";
}

// What made an image (without its sample range); a reference is reused only if this matches.
std::string description(const udm1scene::Scene &scene, const udm1pt::Options &p, int max_depth)
{
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "udm1-pt %s scene %016llx size %dx%d sampler %s spp %u seed %llu randomize %u maxdepth %d strategy %s "
                  "roulette %d near %g loop %s layout %d",
                  udm1_version_string(), (unsigned long long)scene.digest(), p.width, p.height, p.sampler.c_str(), p.spp,
                  (unsigned long long)p.seed, p.randomize, max_depth, strategy_name(p.strategy), p.roulette ? p.rr_depth : -1,
                  p.near_light, p.loop == udm1pt::Loop::Auto ? "auto" : p.loop == udm1pt::Loop::Scalar ? "scalar" : "wavefront",
                  udm1pt::LAYOUT_VERSION);
    return buf;
}

// PNGs are for looking at: clamped to [0, 1] and sRGB-encoded (the EXR keeps the linear radiance).
void write_png(const std::string &path, const udm1pt::Accumulator &a)
{
    std::vector<float> v = a.mean();
    for (float &x : v) {
        double c = std::clamp((double)x, 0.0, 1.0);
        x = (float)(c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055);
    }
    udm1app::write_image(path, v, a.width, a.height, 3, true);
}

std::string mean_text(const udm1pt::Accumulator &a)
{
    std::vector<float> m = a.mean();
    double s[3] = {0, 0, 0};
    for (size_t i = 0; i < m.size(); ++i) s[i % 3] += m[i];
    size_t n = m.size() / 3;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g", s[0] / n, s[1] / n, s[2] / n);
    return buf;
}

int run_compare(const Options &o)
{
    udm1app::LoadedImage a = udm1app::read_image(o.positional[0]), ref = udm1app::read_image(o.positional[1]);
    std::vector<float> diff;
    udm1app::Comparison c = udm1app::compare(a, ref, true, o.diff.empty() ? nullptr : &diff);
    std::printf("mse %.6g rmse %.6g psnr %.4f\n", c.mse, c.rmse, c.psnr);
    if (o.exact) {  // every value of every channel, unclamped, bit for bit (the metadata may differ)
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
    if (!o.diff.empty()) {
        std::vector<float> rgb(diff.size() * 3);
        for (size_t i = 0; i < diff.size(); ++i) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = std::min(1.0f, 10.0f * diff[i]);
        udm1app::write_image(o.diff, rgb, a.width, a.height, 3, true);
    }
    return 0;
}

int run_merge(const Options &o)
{
    for (const std::string &path : {o.output, o.png})
        if (!path.empty()) udm1app::AtomicFile probe(path);
    udm1app::PartialImage p = udm1app::merge_partials(o.positional);
    udm1app::write_partial(o.output, p);
    if (!o.png.empty()) write_png(o.png, p);
    std::printf("merged %zu image(s): samples [%llu, %llu) of %llu\n", o.positional.size(),
                (unsigned long long)p.first, (unsigned long long)(p.first + p.count),
                (unsigned long long)p.spp);
    return 0;
}

int run_sweep(const Options &o, const udm1scene::Scene &scene, const udm1scene::EmbreeScene &rt,
              const udm1pt::Materials &materials)
{
    udm1app::LoadedImage ref = udm1app::read_image(o.against);
    if (ref.width != o.pt.width || ref.height != o.pt.height)
        throw Error("'" + o.against + "' is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                        ", the renders " + std::to_string(o.pt.width) + "x" + std::to_string(o.pt.height),
                    2);
    std::vector<std::string> samplers = o.samplers;
    if (samplers.size() == 1 && samplers[0] == "all") {
        samplers.clear();
        for (size_t k = 0; k < udm1_preset_count(); ++k) {
            udm1_preset_info info;
            if (udm1_preset_get(k, &info) == UDM1_OK && info.max_dimensions >= 2) samplers.push_back(info.name);
        }
    }
    for (const std::string &s : samplers) {
        udm1_preset_info info;
        if (udm1_preset_find(s.c_str(), &info) != UDM1_OK)
            throw Error("unknown sampler '" + s + "' (udm1-seq list shows them)");
    }
    if (!o.images.empty() && (!std::filesystem::is_directory(o.images) || access(o.images.c_str(), W_OK) != 0))
        throw Error("--images '" + o.images + "' is not a writable folder", 1);
    std::printf("sampler,spp,seed,seconds,paths,rays,rmse,psnr,mean_r,mean_g,mean_b\n");
    for (const std::string &s : samplers)
        for (uint32_t spp : o.spps)
            for (uint32_t seed = 1; seed <= o.seeds; ++seed) {
                udm1pt::Options p = o.pt;
                p.sampler = s, p.spp = spp, p.seed = seed, p.first = 0, p.count = 0;
                udm1pt::Stats st;
                udm1pt::Accumulator acc;
                try {
                    acc = udm1pt::render(scene, rt, materials, p, &st);
                } catch (const udm1scene::SceneError &e) {
                    throw Error(e.what(), 1);
                } catch (const std::runtime_error &e) {
                    throw Error(e.what(), 2);
                }
                udm1app::LoadedImage mine;
                mine.width = acc.width, mine.height = acc.height, mine.channels = 3, mine.pixels = acc.mean();
                udm1app::Comparison c = udm1app::compare(mine, ref, true, nullptr);
                std::string m = mean_text(acc);
                for (char &ch : m) ch = ch == ' ' ? ',' : ch;
                std::printf("%s,%u,%u,%.6f,%llu,%llu,%.8g,%.6f,%s\n", s.c_str(), spp, seed, st.seconds,
                            (unsigned long long)st.paths, (unsigned long long)st.rays, c.rmse, c.psnr, m.c_str());
                std::fflush(stdout);
                if (!o.images.empty() && seed == 1) write_png(o.images + "/" + s + "-" + std::to_string(spp) + "spp.png", acc);
            }
    return 0;
}

int run_render(Options o)
{
    std::chrono::steady_clock::time_point load_start;
    std::unique_ptr<udm1pt::Materials> materials;
    udm1scene::Scene scene;
    try {
        load_start = std::chrono::steady_clock::now();
        scene = udm1scene::load_scene(o.scene);
        materials = std::make_unique<udm1pt::Materials>(scene);  // bad materials and textures fail here, before any work
        udm1pt::Lights lights(scene);      // and zero-area lights
        if (!scene.media_where.empty() && scene.integrator == "volpath")
            throw Error(scene.media_where + ": participating media need Integrator \"volpath\", which udm1-pt does not model", 1);
        if (o.command == "render" && !o.spp_given && !scene.sampler_where.empty()) {  // the scene's sample count
            o.pt.spp = (uint32_t)scene.pixel_samples;
            check_sample_range(o);
            scene.notes.push_back(scene.sampler_where + ": " + std::to_string(o.pt.spp) +
                                  " samples per pixel, the Sampler's pixelsamples (--spp overrides); sampler " +
                                  o.pt.sampler + " in place of \"" + scene.sampler + "\" (--sampler chooses)");
        }
        if (!scene.media_where.empty())  // pbrt-v4's PathIntegrator ignores media too
            scene.notes.push_back(scene.media_where + ": media are left out, as Integrator \"path\" leaves them out");
        if (lights.empty()) scene.notes.push_back(o.scene + " has no lights: the image is black");
        if (o.command != "export")
            for (const std::string &n : scene.notes) std::fprintf(stderr, "udm1-pt: note: %s\n", n.c_str());
    } catch (const udm1scene::SceneError &e) {
        throw Error(e.what(), 1);
    }
    if (!o.size_given && scene.source.rfind("builtin:", 0) == 0) o.pt.width = o.pt.height = 256;
    if (o.pt.width == 0) o.pt.width = scene.width, o.pt.height = scene.height;
    if ((uint64_t)o.pt.width * o.pt.height > MAX_PIXELS)
        throw Error(o.scene + ": the film (" + std::to_string(o.pt.width) + "x" + std::to_string(o.pt.height) +
                    ") has more than " + std::to_string(MAX_PIXELS) + " pixels; pass --size", 2);
    int max_depth = o.pt.max_depth >= 0 ? o.pt.max_depth : scene.max_depth;
    if (o.command == "export") {
        udm1pt::export_scene(scene, o.pt.width, o.pt.height, max_depth, o.positional[0]);
        std::printf("wrote %s/scene.json\n", o.positional[0].c_str());
        return 0;
    }
    udm1pt::Accumulator part;
    const std::string made_by = description(scene, o.pt, max_depth);
    if (o.command == "reference") {
        std::FILE *f = std::fopen(o.output.c_str(), "rb");
        if (f) {
            std::fclose(f);
            try {
                udm1app::PartialImage old = udm1app::read_partial(o.output);
                if (old.made_by == made_by && old.first == 0 && old.count == old.spp && old.whole()) {
                    std::printf("reference %s reused (%s)\n", o.output.c_str(), made_by.c_str());
                    if (!o.png.empty()) write_png(o.png, old), std::printf("wrote %s\n", o.png.c_str());
                    return 0;
                }
            } catch (const Error &) {  // not a reference of ours: render it again
            }
        }
    }
    for (const std::string &path : {o.output, o.png})
        if (!path.empty()) udm1app::AtomicFile probe(path);
    if (!o.output.empty()) {
        if (!udm1app::is_exr_path(o.output))
            throw Error("-o '" + o.output + "': udm1-pt writes OpenEXR (.exr); use --png for a PNG", 2);
    }
    udm1scene::EmbreeScene rt(scene);
    double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
    if (o.command == "sweep") return run_sweep(o, scene, rt, *materials);
    udm1pt::Stats st;
    try {
        part = udm1pt::render(scene, rt, *materials, o.pt, &st);
        part.made_by = made_by;
    } catch (const udm1scene::SceneError &e) {
        throw Error(e.what(), 1);
    } catch (const std::runtime_error &e) {
        throw Error(e.what(), 2);
    }
    if (!o.output.empty()) udm1app::write_partial(o.output, part);
    if (!o.png.empty()) write_png(o.png, part);
    std::printf("sampler %s spp %u samples [%llu, %llu) size %dx%d image %dx%d at %d,%d dimensions %u of %u loop %s seconds %.4f "
                "paths %llu rays %llu paths_per_second %.4g rays_per_second %.4g mean %s\n",
                o.pt.sampler.c_str(), o.pt.spp, (unsigned long long)part.first,
                (unsigned long long)(part.first + part.count), part.width, part.height, part.full_width, part.full_height,
                part.x0, part.y0, st.dimensions,
                st.path_dimensions, st.wavefront ? "wavefront" : "scalar", st.seconds, (unsigned long long)st.paths, (unsigned long long)st.rays,
                st.paths / std::max(st.seconds, 1e-9), st.rays / std::max(st.seconds, 1e-9), mean_text(part).c_str());
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    std::printf("scene %zu triangles, %zu shapes, loaded (parse, meshes, textures, BVH) in %.2f s; peak memory %.0f MiB\n",
                scene.triangle_count(), scene.shapes.size(), load_seconds, ru.ru_maxrss / 1024.0);
    if (part.nonfinite || part.clamped)
        std::printf("warning: %llu non-finite and %llu clamped sample values\n", (unsigned long long)part.nonfinite,
                    (unsigned long long)part.clamped);
    for (const std::string &path : {o.output, o.png})
        if (!path.empty()) std::printf("wrote %s\n", path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    return udm1app::run_tool("udm1-pt", [&] {
        Options o = parse(argc, argv);
        std::unique_ptr<tbb::global_control> limit;
        if (o.threads) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        if (o.command == "compare") return run_compare(o);
        if (o.command == "merge") return run_merge(o);
        return run_render(o);
    });
}
