// udm1-noise - Perlin noise and POV-Ray patterns from udm1 sequences, written
// as images (PNG 8/16-bit tagged linear, EXR float, TIFF) and handed to POV-Ray.
//
//   udm1-noise [options] -o texture.png [--pov NAME]
//   udm1-noise figures -o DIR          the paper's Figures 2 and 3: UDM1 tables beside drand48
//
// Errors are one line, "udm1-noise: ...", exit 2 for bad arguments and 1 for
// failures; outputs are written under temporary names and renamed.
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"
#include "udm1app/image_write.h"

#include <udm1/udm1.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

using udm1app::Error;

namespace {

const char *USAGE =
    "usage: udm1-noise [options] [-o FILE.png|.exr|.tif] [--pov NAME]   (no -o: writes noise.png)\n"
    "       udm1-noise figures -o DIR\n"
    "options:\n"
    "  --pattern P     noise, fbm, turbulence, ridged, bozo, bumps, granite, agate, marble, wood,\n"
    "                  wrinkles, leopard, onion, ripples, waves, crackle (default noise)\n"
    "  --table T       perlin, drand48 or a udm1 sampler name (default wr)\n"
    "  --seed S        table seed (default 1)        --kind improved|classic (default improved)\n"
    "  --size WxH      image size (default 512x512)  --scale S  units across the width (default 8)\n"
    "  --origin X,Y,Z  pattern space at the top-left corner (default 0,0,0)\n"
    "  --period P      tileable: the lattice wraps every P units and the image covers exactly P\n"
    "  --octaves N --omega W --lambda L --turbulence T|X,Y,Z --frequency F --phase F\n"
    "  --wave ramp|triangle|sine|scallop|cubic|poly   (POV-Ray's parameters and defaults)\n"
    "  --form A,B,C --metric M --offset O --solid   crackle's (default -1,1,0; 2; 0; not solid)\n"
    "  --colors grey|pov   grey values, or the pattern's POV-Ray default colour map (default grey)\n"
    "  --bits 8|16     PNG/TIFF depth (default 8)    --threads N (default: all cores)\n"
    "  --pov NAME      also write NAME.inc (the pigment) and NAME_demo.pov (a scene using it)\n"
    "  --frames N      a looping animation: N images FILE_0000.png ... over the time w in [0, T): 4D noise\n"
    "                  periodic in w, so the frame after the last is the first (noise, fbm, turbulence, ridged)\n"
    "  --loop T        the loop's length in noise units, an integer (default 4)\n"
    "  --time W        one image at time W of the 4D noise (periodic in --loop)\n"
    "Raw noise patterns (noise, fbm, turbulence, ridged) are written as (1 + v) / 2.\n";

struct Options {
    std::string output, pattern = "noise", table = "wr", pov, figures_dir;
    uint64_t seed = 1;
    uint32_t kind = UDM1_NOISE_IMPROVED, width = 512, height = 512, period = 0, bits = 8, threads = 0;
    uint32_t frames = 0, loop = 4;  // frames 0 and no --time: the 3D pattern
    double scale = 8.0, origin[3] = {0, 0, 0}, time = 0.0;
    bool four_d = false;
    bool pov_colors = false, figures = false;
    udm1_pattern_params params;
};

std::vector<double> parse_vector(const std::string &text, const std::string &what, size_t want_max)
{
    std::vector<double> v;
    size_t start = 0;
    while (true) {
        size_t comma = text.find(',', start);
        v.push_back(udm1app::parse_double(text.substr(start, comma - start), what, -1e300, 1e300));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (v.size() > want_max || (v.size() != 1 && v.size() != want_max))
        throw Error(what + " '" + udm1app::quote_raw(text) + "' needs 1 or " + std::to_string(want_max) + " numbers");
    return v;
}

Options parse(int argc, char **argv)
{
    Options o;
    std::vector<std::string> args(argv + 1, argv + argc);
    size_t i = 0;
    if (!args.empty() && args[0] == "figures") o.figures = true, i = 1;
    if (i < args.size() && (args[i] == "help" || args[i] == "--help")) {  // also "figures --help"
        std::fputs(USAGE, stdout);
        std::exit(0);
    }
    // the pattern first, so that its POV-Ray defaults come before the options that change them
    for (size_t k = i; k + 1 < args.size(); ++k)
        if (args[k] == "--pattern") o.pattern = args[k + 1];
    uint32_t code = udm1_pattern_from_name(o.pattern.c_str());
    if (!code) throw Error("--pattern '" + udm1app::quote_raw(o.pattern) + "' is not a pattern (udm1-noise help lists them)");
    udm1_pattern_params_init(&o.params, code);
    auto value = [&](const std::string &flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + " needs a value");
        return args[++i];
    };
    for (; i < args.size(); ++i) {
        const std::string &a = args[i];
        if (a == "--pattern") value(a);
        else if (a == "-o") {
            o.output = value(a);
            if (o.output.empty()) throw Error("-o needs a file name");
        }
        else if (a == "--table") o.table = value(a);
        else if (a == "--seed") o.seed = udm1app::parse_u64(value(a), "--seed", 0, UINT64_MAX);
        else if (a == "--kind") {
            std::string k = value(a);
            if (k == "improved") o.kind = UDM1_NOISE_IMPROVED;
            else if (k == "classic") o.kind = UDM1_NOISE_CLASSIC;
            else throw Error("--kind '" + udm1app::quote_raw(k) + "' is not improved or classic");
        } else if (a == "--size") {
            int w = 0, h = 0;  // the shared parser: its errors name the whole input
            udm1app::parse_size(value(a), "--size", 16384, (uint64_t)16384 * 16384, &w, &h);
            o.width = (uint32_t)w, o.height = (uint32_t)h;
        } else if (a == "--scale") o.scale = udm1app::parse_double(value(a), "--scale", 1e-9, 1e12);
        else if (a == "--origin") {
            std::vector<double> v = parse_vector(value(a), "--origin", 3);
            for (int c = 0; c < 3; ++c) o.origin[c] = v[v.size() == 1 ? 0 : c];
        } else if (a == "--period") o.period = (uint32_t)udm1app::parse_u64(value(a), "--period", 1, 1u << 30);
        else if (a == "--octaves") o.params.octaves = (uint32_t)udm1app::parse_u64(value(a), "--octaves", 1, 10);
        else if (a == "--omega") o.params.omega = udm1app::parse_double(value(a), "--omega", -100, 100);
        else if (a == "--lambda") o.params.lambda = udm1app::parse_double(value(a), "--lambda", -100, 100);
        else if (a == "--turbulence") {
            std::vector<double> v = parse_vector(value(a), "--turbulence", 3);
            for (int c = 0; c < 3; ++c) o.params.turbulence[c] = v[v.size() == 1 ? 0 : c];
        } else if (a == "--frequency") o.params.frequency = udm1app::parse_double(value(a), "--frequency", -1e6, 1e6);
        else if (a == "--phase") o.params.phase = udm1app::parse_double(value(a), "--phase", -1e6, 1e6);
        else if (a == "--wave") {
            static const char *waves[] = {"default", "ramp", "triangle", "sine", "scallop", "cubic", "poly"};
            std::string w = value(a);
            auto it = std::find_if(std::begin(waves), std::end(waves), [&](const char *n) { return w == n; });
            if (it == std::end(waves)) throw Error("--wave '" + udm1app::quote_raw(w) + "' is not a wave type");
            o.params.wave = (uint32_t)(it - std::begin(waves));
        } else if (a == "--colors") {
            std::string c = value(a);
            if (c != "grey" && c != "pov") throw Error("--colors '" + udm1app::quote_raw(c) + "' is not grey or pov");
            o.pov_colors = c == "pov";
        } else if (a == "--bits") {
            o.bits = (uint32_t)udm1app::parse_u64(value(a), "--bits", 8, 16);
            if (o.bits != 8 && o.bits != 16) throw Error("--bits must be 8 or 16");
        } else if (a == "--threads") o.threads = (uint32_t)udm1app::parse_u64(value(a), "--threads", 1, 1024);
        else if (a == "--form") {
            std::vector<double> v = parse_vector(value(a), "--form", 3);
            for (int c = 0; c < 3; ++c) o.params.crackle_form[c] = v[v.size() == 1 ? 0 : c];
        } else if (a == "--metric") o.params.crackle_metric = udm1app::parse_double(value(a), "--metric", 1, 64);
        else if (a == "--offset") o.params.crackle_offset = udm1app::parse_double(value(a), "--offset", 0, 1e6);
        else if (a == "--solid") o.params.crackle_solid = 1;
        else if (a == "--frames") o.frames = (uint32_t)udm1app::parse_u64(value(a), "--frames", 1, 100000), o.four_d = true;
        else if (a == "--loop") o.loop = (uint32_t)udm1app::parse_u64(value(a), "--loop", 1, 1u << 30);
        else if (a == "--time") o.time = udm1app::parse_double(value(a), "--time", -1e15, 1e15), o.four_d = true;
        else if (a == "--pov") o.pov = value(a);
        else throw Error("unknown option '" + udm1app::quote_raw(a) + "'");
    }
    if (o.output.empty() && o.figures) throw Error("figures needs an output folder: -o DIR");
    if (o.four_d && o.params.pattern > UDM1_PATTERN_RIDGED)
        throw Error("--frames and --time animate 4D noise: --pattern noise, fbm, turbulence or ridged, not '" +
                    udm1app::quote_raw(o.pattern) + "'");
    if (o.four_d && o.kind == UDM1_NOISE_CLASSIC) throw Error("--frames and --time need --kind improved (4D noise)");
    if (o.four_d && !o.pov.empty()) throw Error("--pov writes one texture: not with --frames or --time");
    if (o.output.empty()) o.output = "noise.png";  // the built-in default, as udm1-ao and udm1-pt write theirs
    if (!o.figures) {  // the formats of the usage line, and only those
        std::string ext = o.output.substr(o.output.find_last_of('.') == std::string::npos ? o.output.size()
                                                                                         : o.output.find_last_of('.'));
        for (char &c : ext) c = (char)std::tolower((unsigned char)c);
        if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
            throw Error("-o '" + o.output + "': the texture must be .png, .exr or .tif", 2);
    }
    return o;
}

struct Noise {
    udm1_noise *n = nullptr;
    ~Noise() { udm1_noise_destroy(n); }
};

void make_noise(const std::string &table, uint64_t seed, uint32_t kind, uint32_t period, Noise &out,
                uint32_t period_w = 0)
{
    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    d.table = table.c_str();
    d.seed = seed;
    d.kind = kind;
    d.period[0] = d.period[1] = period;
    d.period_w = period_w;
    if (udm1_noise_create(&d, &out.n) != UDM1_OK) {
        if (table != "perlin" && table != "drand48") {
            udm1_preset_info info;
            if (udm1_preset_find(table.c_str(), &info) != UDM1_OK)
                throw Error("--table '" + udm1app::quote_raw(table) + "' is not perlin, drand48 or a udm1 sampler");
        }
        throw Error(udm1_last_error());
    }
}

bool raw_kind(uint32_t pattern) { return pattern <= UDM1_PATTERN_RIDGED; }

// Evaluate the image, rows in parallel; the result does not depend on the threads.
std::vector<float> render(const udm1_noise *n, const udm1_pattern_params &p, uint32_t w, uint32_t h,
                          const double origin[3], double width_units, double height_units)
{
    std::vector<float> img((size_t)w * h);
    double sx[3] = {width_units / w, 0, 0}, sy[3] = {0, height_units / h, 0};
    udm1_status failed = UDM1_OK;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, h, 8), [&](const tbb::blocked_range<uint32_t> &r) {
        udm1_status st = udm1_pattern_grid(n, &p, w, h, r.begin(), r.end() - r.begin(), origin, sx, sy,
                                           img.data() + (size_t)r.begin() * w);
        if (st != UDM1_OK) failed = st;
    });
    if (failed != UDM1_OK) throw Error(udm1_last_error());
    if (raw_kind(p.pattern))
        for (float &v : img) v = 0.5f * (1.0f + v);
    return img;
}

// The raw patterns in 4D at time w (udm1/noise.h's sums, with udm1_noise_4d in the place of the 3D noise),
// rows in parallel, octave by octave through the batch call.
std::vector<float> render4(const udm1_noise *n, const udm1_pattern_params &p, uint32_t w, uint32_t h,
                           const double origin[3], double width_units, double height_units, double time)
{
    std::vector<float> img((size_t)w * h);
    bool failed = false;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, h, 8), [&](const tbb::blocked_range<uint32_t> &r) {
        std::vector<double> q(4 * (size_t)w), val(w), acc(w);
        for (uint32_t j = r.begin(); j < r.end(); ++j) {
            double b = j + 0.5;
            uint32_t octaves = p.pattern == UDM1_PATTERN_NOISE ? 1 : p.octaves;
            double amp = 1.0, s = 1.0;
            for (uint32_t k = 0; k < octaves; ++k) {
                for (uint32_t i = 0; i < w; ++i) {
                    double a = i + 0.5;
                    q[4 * (size_t)i] = (origin[0] + a * width_units / w) * s;
                    q[4 * (size_t)i + 1] = (origin[1] + b * height_units / h) * s;
                    q[4 * (size_t)i + 2] = origin[2] * s;
                    q[4 * (size_t)i + 3] = time * s;
                }
                const double *axes[4] = {q.data(), q.data() + 1, q.data() + 2, q.data() + 3};
                if (udm1_noise_eval(n, 4, axes, 4, w, val.data(), nullptr) != UDM1_OK) {
                    failed = true;
                    return;
                }
                for (uint32_t i = 0; i < w; ++i) {
                    double t = val[i];
                    double N = std::min(1.0, std::max(0.0, 0.5 + 0.5 * t));  // POV's Noise
                    switch (p.pattern) {
                    case UDM1_PATTERN_NOISE: acc[i] = t; break;
                    case UDM1_PATTERN_TURBULENCE:
                        acc[i] = k == 0 ? std::min(1.0, std::max(0.0, 2.0 * N - 0.5)) : acc[i] + amp * (2.0 * N - 0.5);
                        break;
                    case UDM1_PATTERN_RIDGED: acc[i] = (k == 0 ? 0.0 : acc[i]) + amp * (1.0 - std::fabs(t)) * (1.0 - std::fabs(t)); break;
                    default: acc[i] = (k == 0 ? 0.0 : acc[i]) + amp * t; break;
                    }
                }
                amp *= p.omega;  // octave k: weight omega^k, scale lambda^k
                s *= p.lambda;
            }
            for (uint32_t i = 0; i < w; ++i) img[(size_t)j * w + i] = 0.5f * (1.0f + (float)acc[i]);
        }
    });
    if (failed) throw Error(udm1_last_error());
    return img;
}

std::vector<float> colorize(const std::vector<float> &grey, uint32_t pattern, bool pov_colors)
{
    if (!pov_colors) return grey;
    const udm1_color_entry *e;
    size_t count;
    udm1_pattern_default_colors(pattern, &e, &count);
    std::vector<float> rgb(grey.size() * 3);
    for (size_t i = 0; i < grey.size(); ++i) udm1_color_map_eval(e, count, grey[i], &rgb[3 * i]);
    return rgb;
}

// The POV-Ray include and demo scene beside the texture, written into inc_file and demo_file (pov_paths).
void write_pov(const Options &o, udm1app::AtomicFile &inc_file, udm1app::AtomicFile &demo_file)
{
    std::string image = o.output.substr(o.output.find_last_of('/') + 1);
    std::string ext = image.substr(image.find_last_of('.') + 1);
    std::string type = ext == "exr" ? "exr" : ext == "tif" || ext == "tiff" ? "tiff" : "png";
    std::string name = o.pov.substr(o.pov.find_last_of('/') + 1);
    std::string inc = "// " + name + ".inc - written by udm1-noise: pattern " + o.pattern + ", table " + o.table +
                      ", seed " + std::to_string(o.seed) + ".\n"
                      "// The image holds linear values: gamma 1.0 keeps POV-Ray from decoding it as sRGB.\n"
                      "// It maps the unit square of the x-y plane; scale it to taste.\n"
                      "#declare " + name + "_pigment = pigment {\n"
                      "  image_map { " + type + " \"" + image + "\" gamma 1.0 interpolate 2 " +
                      (o.period ? "" : "once ") + "}\n}\n";
    std::string demo = "// " + name + "_demo.pov - written by udm1-noise: the texture on a plane, lit flat so the\n"
                       "// rendered pixels equal the texture's values. Render headless:\n"
                       "// (File_Gamma=1.0 writes linear values, comparable with the texture's):\n"
                       "//   povray +I" + name + "_demo.pov +O" + name + "_demo.png +FN +W256 +H256 -D -J File_Gamma=1.0\n"
                       "#version 3.7;\n"
                       "global_settings { assumed_gamma 1.0 }\n"
                       "#include \"" + name + ".inc\"\n"
                       "camera { orthographic location <0.5, 0.5, -1> look_at <0.5, 0.5, 0> right x up y }\n"
                       "plane { z, 0 texture { pigment { " + name + "_pigment } finish { ambient 1 diffuse 0 emission 0 } } }\n";
    inc_file.write(inc);
    demo_file.write(demo);
}

// The paths write_pov writes: NAME.inc and NAME_demo.pov.
std::vector<std::string> pov_paths(const Options &o)
{
    std::string name = o.pov.substr(o.pov.find_last_of('/') + 1);
    std::string dir = o.pov.find('/') == std::string::npos ? "" : o.pov.substr(0, o.pov.find_last_of('/') + 1);
    return {o.pov + ".inc", dir + name + "_demo.pov"};
}

// FILE.png -> FILE_0007.png
std::string frame_name(const std::string &output, uint32_t k)
{
    size_t dot = output.find_last_of('.'), slash = output.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) dot = output.size();
    char num[16];
    std::snprintf(num, sizeof num, "_%04u", k);
    return output.substr(0, dot) + num + output.substr(dot);
}

void run_animation(const Options &o)
{
    Noise noise;
    make_noise(o.table, o.seed, o.kind, o.period, noise, o.loop);
    double wu = o.period ? (double)o.period : o.scale;
    double hu = o.period ? (double)o.period : o.scale * o.height / o.width;
    uint32_t frames = o.frames ? o.frames : 1;
    const bool progress = o.frames > 1 && isatty(2);
    std::vector<udm1app::AtomicFile> files;  // committed together after the last frame: an error leaves none
    files.emplace_back(o.frames ? frame_name(o.output, 0) : o.output);  // a bad path fails before the work
    try {
        for (uint32_t k = 0; k < frames; ++k) {  // frame k at w = k T / N: frame N would be frame 0
            double w = o.frames ? (double)k * o.loop / o.frames : o.time;
            std::vector<float> img = render4(noise.n, o.params, o.width, o.height, o.origin, wu, hu, w);
            std::vector<float> out = colorize(img, o.params.pattern, o.pov_colors);
            if (k > 0) files.emplace_back(frame_name(o.output, k));
            udm1app::write_image(files.back(), out, (int)o.width, (int)o.height, o.pov_colors ? 3 : 1, false, (int)o.bits);
            files.back().finish();
            if (progress) std::fprintf(stderr, "\rudm1-noise: frame %u/%u", k + 1, frames);
        }
    } catch (...) {
        if (progress) std::fprintf(stderr, "\n");  // the error on a line of its own
        throw;
    }
    if (progress) std::fprintf(stderr, "\n");
    udm1app::commit_all(files);
}

void run_single(const Options &o)
{
    if (o.four_d) return run_animation(o);
    Noise noise;
    make_noise(o.table, o.seed, o.kind, o.period, noise);
    double wu = o.period ? (double)o.period : o.scale;
    double hu = o.period ? (double)o.period : o.scale * o.height / o.width;
    std::vector<udm1app::AtomicFile> files;  // the texture and the POV-Ray files, committed together
    files.emplace_back(o.output);
    if (!o.pov.empty())
        for (const std::string &path : pov_paths(o)) files.emplace_back(path);
    std::vector<float> img = render(noise.n, o.params, o.width, o.height, o.origin, wu, hu);
    std::vector<float> out = colorize(img, o.params.pattern, o.pov_colors);
    udm1app::write_image(files[0], out, (int)o.width, (int)o.height, o.pov_colors ? 3 : 1, false, (int)o.bits);
    if (!o.pov.empty()) write_pov(o, files[1], files[2]);
    udm1app::commit_all(files);
}

// The paper's Figures 2 (noise) and 3 (patterns), each panel twice: tables from a
// UDM1 sequence (WR) on the left, from drand48 on the right.
void run_figures(const Options &o)
{
    const std::string dir = o.output + "/";
    std::vector<udm1app::AtomicFile> files;  // committed together: an error leaves none
    for (const char *name : {"figure2.png", "figure3.png", "figures.md"}) files.emplace_back(dir + name);
    struct Panel { const char *pattern; double turb; bool pov; double scale; };
    const std::vector<Panel> fig2 = {{"noise", 0, false, 8}, {"fbm", 0, false, 4}, {"turbulence", 0, false, 4},
                                     {"ridged", 0, false, 4}};
    const std::vector<Panel> fig3 = {{"marble", 0.8, true, 2}, {"wood", 0.08, true, 1.2}, {"granite", 0, false, 2},
                                     {"agate", 0, true, 2},    {"bozo", 0, true, 4},     {"wrinkles", 0, false, 4},
                                     {"ripples", 0, false, 4}, {"leopard", 0, false, 24}};
    const uint32_t S = 256, gap = 8;
    for (int f = 0; f < 2; ++f) {
        const std::vector<Panel> &panels = f == 0 ? fig2 : fig3;
        uint32_t cols = (uint32_t)panels.size(), W = cols * S + (cols - 1) * gap, H = 2 * S + gap;
        std::vector<float> sheet((size_t)W * H * 3, 1.0f);
        for (int row = 0; row < 2; ++row) {
            Noise noise;
            make_noise(row == 0 ? "wr" : "drand48", o.seed, UDM1_NOISE_CLASSIC, 0, noise);
            for (uint32_t c = 0; c < cols; ++c) {
                const Panel &pan = panels[c];
                udm1_pattern_params p;
                udm1_pattern_params_init(&p, udm1_pattern_from_name(pan.pattern));
                p.turbulence[0] = p.turbulence[1] = p.turbulence[2] = pan.turb;
                double origin[3] = {0, 0, 0.5};
                std::vector<float> rgb = colorize(render(noise.n, p, S, S, origin, pan.scale, pan.scale), p.pattern, pan.pov);
                for (uint32_t y = 0; y < S; ++y)
                    for (uint32_t x = 0; x < S; ++x)
                        for (int ch = 0; ch < 3; ++ch) {
                            size_t src = (size_t)y * S + x;
                            float v = pan.pov ? rgb[3 * src + ch] : rgb[src];
                            sheet[(((size_t)row * (S + gap) + y) * W + c * (S + gap) + x) * 3 + ch] = v;
                        }
            }
        }
        udm1app::write_image(files[f], sheet, (int)W, (int)H, 3, true);
    }
    std::string md = "# udm1-noise figures\n\n"
                     "The paper's Figure 2 (noise) and Figure 3 (procedural patterns), re-made with Perlin's classic\n"
                     "gradient noise. Top row of each: tables (permutation and gradients) from the UDM1 sequence WR\n"
                     "(square roots of primes, seed " + std::to_string(o.seed) + "); bottom row: from drand48, the paper's baseline.\n\n"
                     "figure2.png: noise, fBm, turbulence, ridged.\n\n"
                     "figure3.png: marble, wood, granite, agate, bozo, wrinkles, ripples, leopard (POV-Ray 3.7 definitions).\n";
    files[2].write(md);
    udm1app::commit_all(files);
}

}  // namespace

int main(int argc, char **argv)
{
    return udm1app::run_tool("udm1-noise", [&] {
        Options o = parse(argc, argv);
        std::unique_ptr<tbb::global_control> limit;
        if (o.threads) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        if (o.figures) run_figures(o);
        else run_single(o);
        return 0;
    });
}
