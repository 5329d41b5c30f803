// bench_noise.cpp - noise evaluations per second, side by side in one run:
//  - udm1's improved (Perlin 2002) noise in 3D and 2D and classic noise in 3D,
//    one thread, over the same 2^20 random points;
//  - libnoise's gradient noise (noise::GradientCoherentNoise3D, quintic
//    QUALITY_BEST: one Perlin evaluation), one thread, the same points;
//  - a whole 1024 x 1024 image of udm1 noise on one thread and on all threads
//    (TBB over rows, as udm1-noise does).
// FastNoise Lite is measured from Python (bench/bench_noise.py), against
// udm1's batch call in the same run. The "AVX2 only" lines come from a second
// process of this program with UDM1_ISA=avx2 (the library fixes its kernels'
// instruction set once per process), run after the first.
//
// Usage: udm1_bench_noise [--reps R] [--batch-only]
#include <udm1/udm1.h>

#if defined(UDM1_HAVE_LIBNOISE)
#include <libnoise/noise.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

template <class F> double best_rate(F &&f, double count, int reps)
{
    double best = 1e30;
    f();
    for (int r = 0; r < reps; ++r) {
        double t0 = now();
        f();
        best = std::min(best, now() - t0);
    }
    return count / best;
}

volatile double sink;

}  // namespace

int main(int argc, char **argv)
{
    int reps = 7;
    bool batch_only = false;  // the second process: the 3D and 2D batch rates only
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--batch-only") == 0) {
            batch_only = true;
        } else if (std::strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
            reps = std::atoi(argv[++i]);
            if (reps < 1 || reps > 1000) {
                std::fprintf(stderr, "udm1_bench_noise: --reps takes 1..1000\n");
                return 2;
            }
        } else {
            std::fprintf(stderr, "udm1_bench_noise: unknown argument '%s'\n", argv[i]);
            return 2;
        }
    }
    const size_t N = 1u << 20;
    std::vector<double> pts(3 * N), out(N);
    std::mt19937_64 gen(1);
    std::uniform_real_distribution<double> dist(-100.0, 100.0);
    for (double &v : pts) v = dist(gen);

    udm1_noise_desc d;
    udm1_noise_desc_init(&d);
    d.table = "wr";
    udm1_noise *imp = nullptr, *cls = nullptr;
    if (udm1_noise_create(&d, &imp) != UDM1_OK) return 1;
    d.kind = UDM1_NOISE_CLASSIC;
    if (udm1_noise_create(&d, &cls) != UDM1_OK) return 1;

    double r3 = best_rate([&] { udm1_noise_points(imp, 3, pts.data(), N, 3, out.data()); sink = out[7]; }, N, reps);
    double r2 = best_rate([&] { udm1_noise_points(imp, 2, pts.data(), N, 3, out.data()); sink = out[7]; }, N, reps);
    if (batch_only) {
        std::printf("%.6g %.6g %s\n", r3, r2, udm1_isa());
        return 0;
    }
    std::printf("%-44s %14s %10s\n", "evaluations, one thread", "per second", "ratio");
    double rc = best_rate([&] { udm1_noise_points(cls, 3, pts.data(), N, 3, out.data()); sink = out[7]; }, N, reps);
    // the same batch capped at AVX2, in a second process (UDM1_ISA is read once per process)
    double r3a = 0, r2a = 0;
    {
        std::string cmd = "UDM1_ISA=avx2 '" + std::string(argv[0]) + "' --batch-only --reps " + std::to_string(reps);
        FILE *child = popen(cmd.c_str(), "r");
        char isa[32] = "";
        if (!child || std::fscanf(child, "%lf %lf %31s", &r3a, &r2a, isa) != 3) r3a = r2a = 0;
        if (child) pclose(child);
    }
    double rs = best_rate(
        [&] {
            double acc = 0;
            for (size_t i = 0; i < N; ++i) acc += udm1_noise_3d(imp, pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
            sink = acc;
        },
        N, reps);
#if defined(UDM1_HAVE_LIBNOISE)
    double rl = best_rate(
        [&] {
            double acc = 0;
            for (size_t i = 0; i < N; ++i)
                acc += noise::GradientCoherentNoise3D(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2], 0,
                                                      noise::QUALITY_BEST);
            sink = acc;
        },
        N, reps);
    std::printf("%-44s %14.4g %10s\n", "libnoise GradientCoherentNoise3D (anchor)", rl, "1.00");
#else
    double rl = 0;
    std::printf("%-44s %14s\n", "libnoise GradientCoherentNoise3D", "not built (libnoise-dev missing)");
#endif
    auto ratio = [&](double r) { return rl > 0 ? r / rl : 0.0; };
    std::printf("%-44s %14.4g %10.2f\n", "udm1 improved 3D, batch (udm1_noise_points)", r3, ratio(r3));
    std::printf("%-44s %14.4g %10.2f\n", "udm1 improved 3D, per call (udm1_noise_3d)", rs, ratio(rs));
    std::printf("%-44s %14.4g %10.2f\n", "udm1 improved 3D, batch, AVX2 only", r3a, ratio(r3a));
    std::printf("%-44s %14.4g %10.2f\n", "udm1 improved 2D, batch", r2, ratio(r2));
    std::printf("%-44s %14.4g %10.2f\n", "udm1 improved 2D, batch, AVX2 only", r2a, ratio(r2a));
    std::printf("%-44s %14.4g %10.2f\n", "udm1 classic 3D, batch", rc, ratio(rc));

    // whole image: 1024 x 1024 of raw noise, one thread against all
    const uint32_t W = 1024, H = 1024;
    std::vector<float> img((size_t)W * H);
    udm1_pattern_params p;
    udm1_pattern_params_init(&p, UDM1_PATTERN_NOISE);
    const double origin[3] = {0, 0, 0.5}, sx[3] = {16.0 / W, 0, 0}, sy[3] = {0, 16.0 / H, 0};
    auto image = [&] {
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, H, 8), [&](const tbb::blocked_range<uint32_t> &r) {
            udm1_pattern_grid(imp, &p, W, H, r.begin(), r.end() - r.begin(), origin, sx, sy,
                              img.data() + (size_t)r.begin() * W);
        });
        sink = img[5];
    };
    double one, all;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = best_rate(image, (double)W * H, reps);
    }
    all = best_rate(image, (double)W * H, reps);
    unsigned cores = std::thread::hardware_concurrency();
    std::printf("%-44s %14.4g %10s\n", "image 1024^2, 1 thread (pixels/s)", one, "1.00");
    std::printf("%-44s %14.4g %10.2f\n", ("image 1024^2, all " + std::to_string(cores) + " threads").c_str(), all,
                all / one);
    udm1_noise_destroy(imp);
    udm1_noise_destroy(cls);
    return 0;
}
