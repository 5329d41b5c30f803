// udm1-pt - an Embree path tracer in which the sampler is one switch (paper, section 5).
//
//   udm1-pt [options] [-o IMAGE.exr] [--png IMAGE.png]      render (default: built-in Cornell box)
//   udm1-pt reference, merge, compare, sweep                the renderers' shared subcommands
//                                                           (udm1app/renderer.h)
//   udm1-pt export DIR [--scene S] [--size WxH]             the parsed scene as PLY files + scene.json
//
// Errors are one line, "udm1-pt: ...", exit 2 for bad arguments and 1 for failures (a bad scene
// names its file and line); images are written under temporary names and renamed, so a failure
// leaves no partial image.
#include "udm1app/cli.h"
#include "udm1app/image_write.h"
#include "udm1app/renderer.h"
#include "embree_scene.h"
#include "integrator.h"
#include "media.h"
#include "scene_export.h"
#include "scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <sys/resource.h>
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
    "  --checkpoints K1,K2,...|every  with -o NAME.exr, also the prefixes [0, K) of the render as NAME.K.exr\n"
    "                    (every: K = 1 .. N), each sample rendered once\n"
    "  --exr-compression C  zip|none: the .exr outputs zip-compressed (default) or uncompressed (larger files,\n"
    "                    quicker to write and read: many checkpoints)\n"
    "  --seed S          sampler seed (default 1)   --frame F  an animation's frame (its own randomization)\n"
    "  --randomize R     none|default|shift|permute|owen|screen|screen-fixed (screen: blue-noise error across\n"
    "                    pixels, at every spp for Weyl sequences, Z-order at power-of-two spp for sobol and\n"
    "                    sobol-owen; screen-fixed: Weyl, blue at exactly --spp)\n"
    "  --size WxH        image size (default: 256x256 for built-in scenes, else the scene's film)\n"
    "  --maxdepth D      maximum bounces (default: the scene's, pbrt's 5)\n"
    "  --strategy S      mis|nee|bsdf: light found by both (MIS), light sampling, or BSDF sampling\n"
    "  --no-roulette     no Russian roulette\n"
    "  --rr-depth N      roulette from vertex N on (default 3; pbrt-v4's rule is 1)\n"
    "  --solid-angle S   near|always|never: triangle lights sampled by solid angle near the light (default),\n"
    "                    wherever possible (as pbrt-v4), or never (always by area)\n"
    "  --loop L          auto|scalar|wavefront: the path loop (default auto = wavefront: many paths at a time,\n"
    "                    shading in float SIMD for the diffuse subset - triangles, diffuse, area lights, pinhole,\n"
    "                    MIS - else the scalar loop's estimator path by path; scalar: one path at a time)\n"
    "  --threads N       default: all cores\n";

const char *strategy_name(udm1pt::Strategy s)
{
    return s == udm1pt::Strategy::Mis ? "mis" : s == udm1pt::Strategy::Nee ? "nee" : "bsdf";
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

using Clock = std::chrono::steady_clock;

// The path tracer behind the shared front end.
class PtRenderer final : public udm1app::Renderer {
public:
    const Defaults &defaults() const override { return defaults_; }

    bool option(const std::string &flag, const std::function<std::string()> &value, udm1app::RenderSettings &) override
    {
        if (flag == "--maxdepth") pt_.max_depth = (int)udm1app::parse_u64(value(), flag, 0, 1000);
        else if (flag == "--strategy")
            pt_.strategy = udm1app::parse_choice<udm1pt::Strategy>(
                value(), flag, {{"mis", udm1pt::Strategy::Mis}, {"nee", udm1pt::Strategy::Nee}, {"bsdf", udm1pt::Strategy::Bsdf}});
        else if (flag == "--no-roulette") pt_.roulette = false;
        else if (flag == "--loop")
            pt_.loop = udm1app::parse_choice<udm1pt::Loop>(
                value(), flag, {{"auto", udm1pt::Loop::Auto}, {"scalar", udm1pt::Loop::Scalar}, {"wavefront", udm1pt::Loop::Wavefront}});
        else if (flag == "--rr-depth") pt_.rr_depth = (int)udm1app::parse_u64(value(), flag, 0, 1000);
        else if (flag == "--solid-angle")
            pt_.near_light = udm1app::parse_choice<double>(
                value(), flag, {{"near", udm1pt::Lights::NEAR_DEFAULT}, {"always", 0.0}, {"never", HUGE_VAL}});
        else return false;
        return true;
    }

    void load(udm1app::RenderSettings &s) override
    {
        Clock::time_point start = Clock::now();
        try {
            scene_ = udm1scene::load_scene(s.scene);
            materials_ = std::make_unique<udm1pt::Materials>(scene_);  // bad materials and textures fail here
            udm1pt::Lights lights(scene_);                              // and zero-area lights
            if (s.command == "render" && !s.spp_given && !scene_.sampler_where.empty()) {  // the scene's sample count
                s.spp = (uint32_t)scene_.pixel_samples;
                udm1app::check_sample_range(s);  // before the notes: a bad range is the one line
                scene_.notes.push_back(scene_.sampler_where + ": " + std::to_string(s.spp) +
                                       " samples per pixel, the Sampler's pixelsamples (--spp overrides); sampler " +
                                       s.sampler + " in place of \"" + scene_.sampler + "\" (--sampler chooses)");
            }
            if (!scene_.media_where.empty() && scene_.integrator != "volpath")  // pbrt-v4's PathIntegrator ignores media too
                scene_.notes.push_back(scene_.media_where + ": media are left out, as Integrator \"path\" leaves them out");
            if (lights.empty() && !udm1pt::emissive_media(scene_))
                scene_.notes.push_back(s.scene + " has no lights: the image is black");
            if (s.command != "export")
                for (const std::string &n : scene_.notes) std::fprintf(stderr, "udm1-pt: note: %s\n", n.c_str());
        } catch (const udm1scene::SceneError &e) {
            throw Error(e.what(), 1);
        }
        if (!s.size_given && scene_.source.rfind("builtin:", 0) == 0) s.width = s.height = 256;
        if (s.width == 0) s.width = scene_.width, s.height = scene_.height;
        if (scene_.has_crop || scene_.has_pixel_bounds) {  // the image is the Film's window of the film (--size's)
            int w[4];
            try {
                scene_.film_window(s.width, s.height, w);
            } catch (const udm1scene::SceneError &e) {
                throw Error(e.what(), 1);
            }
            pt_.film_width = s.width, pt_.film_height = s.height, pt_.film_x0 = w[0], pt_.film_y0 = w[1];
            if (s.command != "export")
                std::fprintf(stderr, "udm1-pt: note: %s: the image is the Film's %s, pixels [%d, %d) x [%d, %d) of the %dx%d film, "
                                     "as pbrt-v4 renders it\n",
                             scene_.source.c_str(), scene_.has_crop ? "cropwindow" : "pixelbounds", w[0], w[2], w[1], w[3],
                             s.width, s.height);
            s.width = w[2] - w[0], s.height = w[3] - w[1];
        }
        load_seconds_ = std::chrono::duration<double>(Clock::now() - start).count();
    }

    std::string describe(const udm1app::RenderSettings &s) const override
    {
        udm1pt::Options p = options(s);
        char buf[512];
        std::snprintf(buf, sizeof buf,
                      "udm1-pt %s scene %016llx size %dx%d sampler %s spp %u seed %llu randomize %u maxdepth %d strategy %s "
                      "roulette %d near %g loop %s layout %d",
                      udm1_version_string(), (unsigned long long)scene_.digest(), p.width, p.height, p.sampler.c_str(),
                      p.spp, (unsigned long long)p.seed, p.randomize, max_depth(), strategy_name(p.strategy),
                      p.roulette ? p.rr_depth : -1, p.near_light,
                      p.loop == udm1pt::Loop::Auto ? "auto" : p.loop == udm1pt::Loop::Scalar ? "scalar" : "wavefront",
                      udm1pt::LAYOUT_VERSION);
        if (p.film_width > 0)  // a crop: which window of which film
            return buf + (" film " + std::to_string(p.film_width) + "x" + std::to_string(p.film_height) + " at " +
                          std::to_string(p.film_x0) + "," + std::to_string(p.film_y0));
        return buf;
    }

    udm1app::PartialImage render(const udm1app::RenderSettings &s, udm1app::RenderStats *stats) override
    {
        if (!rt_) {
            Clock::time_point start = Clock::now();
            rt_ = std::make_unique<udm1scene::EmbreeScene>(scene_);
            load_seconds_ += std::chrono::duration<double>(Clock::now() - start).count();
        }
        udm1pt::Accumulator acc;
        try {
            acc = udm1pt::render(scene_, *rt_, *materials_, options(s), &stats_);
            rt_->check("rendering");
        } catch (const udm1scene::SceneError &e) {
            throw Error(e.what(), 1);
        } catch (const std::runtime_error &e) {
            throw Error(e.what(), 2);
        }
        stats->seconds = stats_.seconds;
        stats->columns = {{"paths", std::to_string(stats_.paths)}, {"rays", std::to_string(stats_.rays)}};
        std::string m = mean_text(acc);
        size_t a = m.find(' '), b = m.find(' ', a + 1);
        stats->after = {{"mean_r", m.substr(0, a)}, {"mean_g", m.substr(a + 1, b - a - 1)}, {"mean_b", m.substr(b + 1)}};
        acc.made_by = describe(s);
        return acc;
    }

    void report(const udm1app::RenderSettings &s, const udm1app::PartialImage &part,
                const udm1app::RenderStats &) override
    {
        const udm1pt::Stats &st = stats_;
        std::printf("sampler %s spp %u samples [%llu, %llu) size %dx%d image %dx%d at %d,%d dimensions %u of %u loop %s "
                    "seconds %.4f paths %llu rays %llu paths_per_second %.4g rays_per_second %.4g mean %s\n",
                    s.sampler.c_str(), s.spp, (unsigned long long)part.first, (unsigned long long)(part.first + part.count),
                    part.width, part.height, part.full_width, part.full_height, part.x0, part.y0, st.dimensions,
                    st.path_dimensions, st.loop, st.seconds, (unsigned long long)st.paths,
                    (unsigned long long)st.rays, st.paths / std::max(st.seconds, 1e-9), st.rays / std::max(st.seconds, 1e-9),
                    mean_text(part).c_str());
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        std::printf("scene %zu triangles, %zu shapes, loaded (parse, meshes, textures, BVH) in %.2f s; peak memory %.0f MiB\n",
                    scene_.triangle_count(), scene_.shapes.size(), load_seconds_, ru.ru_maxrss / 1024.0);
        if (part.nonfinite || part.clamped)
            std::printf("warning: %llu non-finite and %llu clamped sample values\n", (unsigned long long)part.nonfinite,
                        (unsigned long long)part.clamped);
    }

    // PNGs are for looking at: clamped to [0, 1] and sRGB-encoded (the EXR keeps the linear radiance).
    std::vector<float> display(const udm1app::PartialImage &img, bool *srgb) const override
    {
        std::vector<float> v = img.mean();
        for (float &x : v) {
            double c = std::clamp((double)x, 0.0, 1.0);
            x = (float)(c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055);
        }
        *srgb = true;
        return v;
    }

    bool owns(const udm1app::PartialImage &img) const override
    {
        return img.channels == std::vector<std::string>{"R", "G", "B"} ||
               img.channels == std::vector<std::string>{"R", "G", "B", "W"};
    }

    void check_sampler(const std::string &name) const override
    {
        udm1_preset_info info;
        if (udm1_preset_find(name.c_str(), &info) != UDM1_OK)
            throw Error("unknown sampler '" + name + "' (udm1-seq list shows them)");
    }

    int run_command(const udm1app::RenderSettings &s) override  // export
    {
        if (s.positional.size() != 1) throw Error("export needs one folder");
        if (pt_.film_width > 0) throw Error(scene_.source + ": export writes whole films, not a Film's cropwindow or pixelbounds", 1);
        if (udm1pt::uses_media(scene_))  // (scene.json has surfaces only: the other renderer would leave the media out)
            throw Error(scene_.media_where + ": export writes no participating media (Integrator \"volpath\" renders them)", 1);
        udm1pt::export_scene(scene_, s.width, s.height, max_depth(), s.positional[0]);
        std::printf("wrote %s/scene.json\n", s.positional[0].c_str());
        return 0;
    }

private:
    int max_depth() const { return pt_.max_depth >= 0 ? pt_.max_depth : scene_.max_depth; }

    udm1pt::Options options(const udm1app::RenderSettings &s) const { return udm1app::with_settings(pt_, s); }

    Defaults defaults_{"udm1-pt", USAGE, "pt.png", "sobol-owen", 16, "sobol-owen", 4096, 1u << 24, {"export"}};
    udm1pt::Options pt_;
    udm1scene::Scene scene_;
    std::unique_ptr<udm1pt::Materials> materials_;
    std::unique_ptr<udm1scene::EmbreeScene> rt_;
    udm1pt::Stats stats_;
    double load_seconds_ = 0;
};

}  // namespace

int main(int argc, char **argv) { return udm1app::renderer_main<PtRenderer>(argc, argv); }
