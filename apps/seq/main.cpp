// udm1-seq - dump, measure and draw any udm1 sampler.
//
//   udm1-seq list
//   udm1-seq dump SAMPLER -n N [-d D] [-o points.csv|points.npy]
//   udm1-seq metrics SAMPLER -n N [-d D] [--reps R]
//   udm1-seq plot SAMPLER -n N -o points.png [--dims A,B] [--size PIXELS]
//   udm1-seq spectrum SAMPLER -n N -o spectrum.png [--size S] [--reps R]
//   udm1-seq zoneplate SAMPLER --spp S -o zoneplate.png [--width W] [--height H]
//   udm1-seq check SAMPLER -d D -n N
//
// Common options: --seed S, --stream S, --first F, --randomize
// none|default|shift|permute|owen. A point-set sampler gets K = N points.
// Errors are one line, "udm1-seq: ...", exit 2 for bad arguments and 1 for
// failures; an output file is written under a temporary name and renamed.
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"
#include "udm1app/image_write.h"

#include <udm1/udm1.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

using udm1app::Error;

namespace {

const char *USAGE =
    "usage: udm1-seq COMMAND [SAMPLER] [options]   (no arguments: plot wr -o seq.png)\n"
    "commands:\n"
    "  list                         the samplers (presets) and what they are\n"
    "  dump SAMPLER                 points as CSV (default, to stdout) or .npy (-o)\n"
    "  metrics SAMPLER              discrepancies, star discrepancy, minimum distance, integration RMSE\n"
    "  plot SAMPLER -o F.png        the points of dimensions --dims A,B (default 0,1)\n"
    "  spectrum SAMPLER -o F.png    the power spectrum of dimensions 0,1 over --reps randomizations\n"
    "  zoneplate SAMPLER -o F.png   the zone plate test, --spp samples per pixel\n"
    "  check SAMPLER                the constant-set check of a Weyl sampler\n"
    "options:\n"
    "  -n N          points (default 256)            -d D        dimensions (default 2)\n"
    "  --seed S      seed (default 1)                --stream S  stream / pixel id (default 0)\n"
    "  --first F     first index (default 0)         --reps R    randomizations (default 16)\n"
    "  --randomize none|default|shift|permute|owen|screen (default: default; screen: progressive\n"
    "                screen-space shifts, pixel (x, y) as stream (y << 32) | x, Weyl sequences)\n"
    "  --size S      image size (plot 512, spectrum 128)\n"
    "  --width W --height H --spp S   zone plate (512 x 512, 16 spp)\n"
    "  -o FILE       output file (.csv, .npy, .png, .exr, .tif)\n";

struct Options {
    std::string command, sampler, output;
    uint64_t n = 256, seed = 1, stream = 0, first = 0;
    uint32_t d = 2, reps = 16, randomize = UDM1_RANDOMIZE_DEFAULT, size = 0, width = 512, height = 512, spp = 16;
    uint32_t dim_a = 0, dim_b = 1;
    bool d_given = false;
};

Options parse(int argc, char **argv)
{
    Options o;
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) args = {"plot", "wr", "-o", "seq.png"};  // the built-in default: WR's first 256 points
    o.command = args[0];
    for (const std::string &a : args)  // "udm1-seq COMMAND ... --help"
        if (a == "--help") {
            o.command = "help";
            return o;
        }
    size_t i = 1;
    if (o.command != "list" && o.command != "help" && o.command != "--help") {
        if (i >= args.size() || args[i].rfind("-", 0) == 0) throw Error("'" + udm1app::quote_raw(o.command) + "' needs a SAMPLER name");
        o.sampler = args[i++];
    }
    auto value = [&](const std::string &flag) -> std::string {
        if (i + 1 >= args.size()) throw Error(flag + " needs a value");
        return args[++i];
    };
    for (; i < args.size(); ++i) {
        const std::string &a = args[i];
        if (a == "-n") o.n = udm1app::parse_u64(value(a), "-n", 1, UDM1_MAX_POINT_COUNT);
        else if (a == "-d") o.d = (uint32_t)udm1app::parse_u64(value(a), "-d", 1, UDM1_MAX_DIMENSIONS), o.d_given = true;
        else if (a == "--seed") o.seed = udm1app::parse_u64(value(a), "--seed", 0, UINT64_MAX);
        else if (a == "--stream") o.stream = udm1app::parse_u64(value(a), "--stream", 0, UINT64_MAX);
        else if (a == "--first") o.first = udm1app::parse_u64(value(a), "--first", 0, UINT64_MAX);
        else if (a == "--reps") o.reps = (uint32_t)udm1app::parse_u64(value(a), "--reps", 1, 100000);
        else if (a == "--randomize") o.randomize = udm1app::parse_randomize(value(a));
        else if (a == "--size") o.size = (uint32_t)udm1app::parse_u64(value(a), "--size", 2, 4096);
        else if (a == "--width") o.width = (uint32_t)udm1app::parse_u64(value(a), "--width", 1, 16384);
        else if (a == "--height") o.height = (uint32_t)udm1app::parse_u64(value(a), "--height", 1, 16384);
        else if (a == "--spp") o.spp = (uint32_t)udm1app::parse_u64(value(a), "--spp", 1, 1u << 20);
        else if (a == "-o") o.output = value(a);
        else if (a == "--dims") {
            std::string v = value(a);
            size_t comma = v.find(',');
            if (comma == std::string::npos) throw Error("--dims '" + udm1app::quote_raw(v) + "' is not two dimensions A,B");
            o.dim_a = (uint32_t)udm1app::parse_u64(v.substr(0, comma), "--dims", 0, UDM1_MAX_DIMENSIONS - 1);
            o.dim_b = (uint32_t)udm1app::parse_u64(v.substr(comma + 1), "--dims", 0, UDM1_MAX_DIMENSIONS - 1);
        } else {
            throw Error("unknown option '" + udm1app::quote_raw(a) + "'");
        }
    }
    return o;
}

struct Seq {
    udm1_seq *s = nullptr;
    ~Seq() { udm1_seq_destroy(s); }
};

// Create the sampler of the options with `dims` dimensions and K = points for point sets.
void make(const Options &o, uint32_t dims, uint64_t points, Seq &seq)
{
    udm1_preset_info info;
    if (udm1_preset_find(o.sampler.c_str(), &info) != UDM1_OK)
        throw Error("unknown sampler '" + udm1app::quote_raw(o.sampler) + "' (udm1-seq list shows them)");
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = o.sampler.c_str();
    desc.dimensions = dims;
    desc.point_count = (info.flags & UDM1_PRESET_POINT_SET) ? points : 0;
    desc.seed = o.seed;
    if (o.randomize == udm1app::RANDOMIZE_SCREEN_FIXED)
        throw Error("--randomize screen-fixed is the renderers' (it needs their spp); udm1-seq takes screen");
    desc.randomize = o.randomize;
    if (udm1_seq_create_desc(&desc, &seq.s) != UDM1_OK) throw Error(udm1_last_error());
}

void need_output(const Options &o)
{
    if (o.output.empty()) throw Error("'" + o.command + "' needs an output file: -o FILE");
}

std::vector<double> points(const Options &o, const Seq &seq, uint32_t d0, uint32_t nd)
{
    std::vector<double> p((size_t)o.n * nd);
    if (udm1_seq_fill_f64(seq.s, o.stream, o.first, (size_t)o.n, d0, nd, p.data(), nd) != UDM1_OK)
        throw Error(udm1_last_error());
    return p;
}

void cmd_list()
{
    static const char *modes[] = {"none", "default", "shift", "permute", "owen"};
    std::printf("%-12s %-9s %-9s %-11s %s\n", "sampler", "max dims", "kind", "randomized", "description");
    for (size_t i = 0; i < udm1_preset_count(); ++i) {
        udm1_preset_info p;
        udm1_preset_get(i, &p);
        udm1_seq_desc desc;
        udm1_seq_desc_init(&desc);
        desc.preset = p.name;
        desc.dimensions = 1;
        desc.point_count = (p.flags & UDM1_PRESET_POINT_SET) ? 16 : 0;
        udm1_seq *s = nullptr;
        const char *mode = "?";
        if (udm1_seq_create_desc(&desc, &s) == UDM1_OK) mode = modes[udm1_seq_randomization(s)];
        udm1_seq_destroy(s);
        std::printf("%-12s %-9u %-9s %-11s %s\n", p.name, p.max_dimensions,
                    (p.flags & UDM1_PRESET_POINT_SET) ? "point set" : "sequence",
                    std::strcmp(mode, "default") == 0 ? "streams" : mode, p.description);
    }
}

void write_npy(const std::string &path, const std::vector<double> &p, uint64_t n, uint32_t d)
{
    udm1app::AtomicFile file(path);
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(n) + ", " +
                         std::to_string(d) + "), }";
    size_t total = 10 + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header += '\n';
    const char magic[] = "\x93NUMPY\x01\x00";
    file.write(magic, 8);
    uint16_t len = (uint16_t)header.size();
    unsigned char lenb[2] = {(unsigned char)(len & 0xff), (unsigned char)(len >> 8)};
    file.write(lenb, 2);
    file.write(header);
    file.write(p.data(), p.size() * sizeof(double));
    file.commit();
}

void cmd_dump(const Options &o)
{
    Seq seq;
    make(o, o.d, o.n, seq);
    std::vector<double> p = points(o, seq, 0, o.d);
    bool npy = o.output.size() > 4 && o.output.compare(o.output.size() - 4, 4, ".npy") == 0;
    if (npy) return write_npy(o.output, p, o.n, o.d);
    std::string text;
    char buf[32];
    for (uint64_t i = 0; i < o.n; ++i) {
        for (uint32_t j = 0; j < o.d; ++j) {
            std::snprintf(buf, sizeof buf, "%.17g", p[i * o.d + j]);
            text += buf;
            text += j + 1 < o.d ? ',' : '\n';
        }
    }
    if (o.output.empty() || o.output == "-") {
        std::fwrite(text.data(), 1, text.size(), stdout);
        return;
    }
    udm1app::AtomicFile file(o.output);
    file.write(text);
    file.commit();
}

void cmd_metrics(const Options &o)
{
    Seq seq;
    make(o, o.d, o.n, seq);
    std::vector<double> p = points(o, seq, 0, o.d);
    static const struct { const char *name; uint32_t kind; } disc[] = {{"L2-star", UDM1_DISCREPANCY_L2_STAR},
                                                                       {"CD", UDM1_DISCREPANCY_CENTERED},
                                                                       {"WD", UDM1_DISCREPANCY_WRAP_AROUND},
                                                                       {"MD", UDM1_DISCREPANCY_MIXTURE}};
    std::printf("sampler %s, n = %llu, d = %u, stream %llu, seed %llu\n", o.sampler.c_str(),
                (unsigned long long)o.n, o.d, (unsigned long long)o.stream, (unsigned long long)o.seed);
    std::printf("%-44s %12s %12s\n", "metric", "value", "random");
    for (auto &k : disc) {
        double v = 0, r = 0;
        if (udm1_discrepancy(p.data(), o.n, o.d, o.d, k.kind, &v) != UDM1_OK) throw Error(udm1_last_error());
        udm1_discrepancy_random(o.n, o.d, k.kind, &r);
        std::printf("%-44s %12.4g %12.4g\n", (std::string(k.name) + " discrepancy").c_str(), v, r);
    }
    if (o.d >= 2 && o.n <= 16384) {
        std::vector<double> two = points(o, seq, 0, 2);
        double v = 0;
        if (udm1_star_discrepancy_2d(two.data(), o.n, 2, &v) != UDM1_OK) throw Error(udm1_last_error());
        std::printf("%-44s %12.4g\n", "star discrepancy (dims 0,1)", v);
    }
    if (o.n >= 2 && o.d >= 2) {
        std::vector<double> two = points(o, seq, 0, 2);
        double v = 0;
        if (udm1_min_distance(two.data(), o.n, 2, 2, 1, &v) != UDM1_OK) throw Error(udm1_last_error());
        std::printf("%-44s %12.4g\n", "min toroidal distance x sqrt(n) (dims 0,1)", v * std::sqrt((double)o.n));
    }
    for (uint32_t k = 1; udm1_integrand_name(k); ++k) {
        bool two_d = k <= UDM1_INTEGRAND_STEP;
        uint32_t d = two_d ? 2 : o.d;
        if ((two_d && o.d < 2) || (k == UDM1_INTEGRAND_GENZ_CORNER_PEAK && d > 20) ||
            (k == UDM1_INTEGRAND_GENZ_DISCONTINUOUS && d < 2))
            continue;
        double rmse = 0, exact = 0;
        if (udm1_integration_error(seq.s, k, d, o.n, o.reps, &rmse, nullptr) != UDM1_OK) throw Error(udm1_last_error());
        udm1_integrand_exact(k, d, &exact);
        char label[64];
        std::snprintf(label, sizeof label, "relative RMSE %s (d=%u, R=%u)", udm1_integrand_name(k), d, o.reps);
        std::printf("%-44s %12.4g\n", label, rmse / std::fabs(exact));
    }
}

void cmd_plot(const Options &o)
{
    need_output(o);
    uint32_t dims = std::max(o.dim_a, o.dim_b) + 1;
    Seq seq;
    make(o, std::max(dims, o.d_given ? o.d : dims), o.n, seq);
    std::vector<double> a = points(o, seq, o.dim_a, 1), b = points(o, seq, o.dim_b, 1);
    int S = o.size ? (int)o.size : 512;
    std::vector<float> img((size_t)S * S * 3, 1.0f);
    for (int k = 1; k < 8; ++k) // a light grid of eighths
        for (int t = 0; t < S; ++t)
            for (int c = 0; c < 3; ++c) {
                int g = k * S / 8;
                img[((size_t)g * S + t) * 3 + c] = img[((size_t)t * S + g) * 3 + c] = 0.85f;
            }
    float radius = std::max(1.0f, std::min(4.0f, 0.35f * S / std::sqrt((float)o.n)));
    for (uint64_t i = 0; i < o.n; ++i) {
        float cx = (float)a[i] * S, cy = (1.0f - (float)b[i]) * S;
        for (int y = (int)(cy - radius - 1); y <= (int)(cy + radius + 1); ++y)
            for (int x = (int)(cx - radius - 1); x <= (int)(cx + radius + 1); ++x) {
                if (x < 0 || y < 0 || x >= S || y >= S) continue;
                float dx = x + 0.5f - cx, dy = y + 0.5f - cy, cover = radius + 0.5f - std::sqrt(dx * dx + dy * dy);
                if (cover <= 0) continue;
                cover = std::min(cover, 1.0f);
                static const float ink[3] = {0.12f, 0.30f, 0.47f};
                for (int c = 0; c < 3; ++c) {
                    float &v = img[((size_t)y * S + x) * 3 + c];
                    v = v * (1 - cover) + ink[c] * cover;
                }
            }
    }
    udm1app::write_image(o.output, img, S, S, 3, true);
}

void cmd_spectrum(const Options &o)
{
    need_output(o);
    Seq seq;
    make(o, std::max<uint32_t>(2, o.d_given ? o.d : 2), o.n, seq);
    uint32_t S = o.size ? o.size : 128;
    if (S % 2 || S > 1024) throw Error("--size " + std::to_string(S) + " must be even and at most 1024 for a spectrum");
    std::vector<double> sp((size_t)S * S);
    if (udm1_spectrum_2d(seq.s, 0, o.n, o.reps, S, sp.data()) != UDM1_OK) throw Error(udm1_last_error());
    // tone map: P = 1 (white noise) is mid grey; log scale over 2 decades each way
    std::vector<float> img(sp.size());
    for (size_t k = 0; k < sp.size(); ++k)
        img[k] = (float)std::clamp(0.5 + std::log10(std::max(sp[k], 1e-12)) / 4.0, 0.0, 1.0);
    udm1app::write_image(o.output, img, (int)S, (int)S, 1, true);
}

void cmd_zoneplate(const Options &o)
{
    need_output(o);
    Seq seq;
    make(o, std::max<uint32_t>(2, o.d_given ? o.d : 2), o.spp, seq);
    std::vector<float> img((size_t)o.width * o.height);
    if (udm1_zoneplate(seq.s, 0, o.width, o.height, o.spp, img.data()) != UDM1_OK) throw Error(udm1_last_error());
    udm1app::write_image(o.output, img, (int)o.width, (int)o.height, 1, true);
}

void cmd_check(const Options &o)
{
    Seq seq;
    make(o, o.d, o.n, seq);
    udm1_alpha_report r;
    if (udm1_seq_check(seq.s, o.n, &r) != UDM1_OK) throw Error(udm1_last_error());
    std::printf("%s\n", r.message);
}

}  // namespace

int main(int argc, char **argv)
{
    return udm1app::run_tool("udm1-seq", [&] {
        Options o = parse(argc, argv);
        if (o.command == "list") cmd_list();
        else if (o.command == "help" || o.command == "--help") std::fputs(USAGE, stdout);
        else if (o.command == "dump") cmd_dump(o);
        else if (o.command == "metrics") cmd_metrics(o);
        else if (o.command == "plot") cmd_plot(o);
        else if (o.command == "spectrum") cmd_spectrum(o);
        else if (o.command == "zoneplate") cmd_zoneplate(o);
        else if (o.command == "check") cmd_check(o);
        else throw Error("unknown command '" + udm1app::quote_raw(o.command) + "' (udm1-seq help lists them)");
        return 0;
    });
}
