// udm1-ao - ambient occlusion with any udm1 sampler on Embree (paper, section 4.2).
//
//   udm1-ao [options] [-o ao.exr] [--png ao.png]       render (default: built-in Cornell box, episwr, 64 spp)
//   udm1-ao reference -o ref.exr [options]             a high-spp reference (default sobol-owen, 8192 spp),
//                                                      rendered only if ref.exr was not made by the same settings
//   udm1-ao merge, compare, sweep                      as udm1-pt (udm1app/renderer.h)
//
// Errors are one line, "udm1-ao: ...", exit 2 for bad arguments and 1 for
// failures (an unreadable scene names its file and line); outputs are written
// under temporary names and renamed, so a failure leaves no partial image.
#include "udm1app/cli.h"
#include "udm1app/renderer.h"
#include "ao_render.h"
#include "embree_scene.h"
#include "scene.h"

#include <algorithm>
#include <cstdio>
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
    "  --checkpoints K1,K2,...|every  with -o NAME.exr, also the prefixes [0, K) of the render as NAME.K.exr\n"
    "                  (every: K = 1 .. N), each sample rendered once\n"
    "  --exr-compression C  zip|none: the .exr outputs zip-compressed (default) or uncompressed (larger files,\n"
    "                  quicker to write and read: many checkpoints)\n"
    "  --randomize R   none|default|shift|permute|owen|screen|screen-fixed (default: the sampler's own;\n"
    "                  screen: blue-noise error across pixels, at every spp for Weyl sequences, Z-order at\n"
    "                  power-of-two spp for sobol/sobol-owen; screen-fixed: Weyl, blue at exactly --spp)\n"
    "  --frame F       an animation's frame F: its own randomization (default 0)\n"
    "  --size WxH      image size (default: 256x256 for built-in scenes, else the scene's film)\n"
    "  --maxdist D     occlusion ray length (default: unbounded)\n"
    "  --jitter        jitter the primary ray too (4D: dims 0,1 pixel, 2,3 direction)\n"
    "  --direction-dims D  without --jitter: the direction from dims D, D + 1 (D even; default 0)\n"
    "  --method M      single|packet|stream: how occlusion rays go to Embree (default stream, the fastest)\n"
    "  --threads N     default: all cores\n"
    "prints one line: sampler, spp, seconds, rays per second.\n";

// The ambient occlusion renderer behind the shared front end.
class AoRenderer final : public udm1app::Renderer {
public:
    const Defaults &defaults() const override { return defaults_; }

    bool option(const std::string &flag, const std::function<std::string()> &value, udm1app::RenderSettings &) override
    {
        if (flag == "--maxdist") ao_.max_distance = udm1app::parse_double(value(), flag, 1e-12, 1e300);
        else if (flag == "--jitter") ao_.jitter = true;
        else if (flag == "--direction-dims") {
            ao_.direction_dim = (uint32_t)udm1app::parse_u64(value(), flag, 0, 1024);
            if (ao_.direction_dim % 2) throw udm1app::Error("--direction-dims " + std::to_string(ao_.direction_dim) + " is odd");
        }
        else if (flag == "--method")
            ao_.method = udm1app::parse_choice<udm1ao::Method>(
                value(), flag, {{"single", udm1ao::Method::Single}, {"packet", udm1ao::Method::Packet},
                                {"stream", udm1ao::Method::Stream}});
        else return false;
        return true;
    }

    void load(udm1app::RenderSettings &s) override
    {
        try {
            scene_ = udm1scene::load_scene(s.scene, udm1scene::Need::Geometry);
        } catch (const udm1scene::SceneError &e) {
            throw Error(e.what(), 1);
        }
        if (!scene_.ignored.empty())  // one line: what ambient occlusion does not need
            std::fprintf(stderr, "udm1-ao: note: %zu kind(s) of appearance left out, first %s\n", scene_.ignored.size(),
                         scene_.ignored[0].c_str());
        for (const std::string &n : scene_.notes) std::fprintf(stderr, "udm1-ao: note: %s\n", n.c_str());
        if (!s.size_given && scene_.source.rfind("builtin:", 0) == 0) s.width = s.height = 256;
        if (s.width == 0) s.width = scene_.width, s.height = scene_.height;
    }

    std::string describe(const udm1app::RenderSettings &s) const override
    {
        // the ray method and thread count are left out: they do not change the image (tested)
        udm1ao::Options a = options(s);
        char buf[512];
        std::snprintf(buf, sizeof buf,
                      "udm1-ao %s scene %016llx size %dx%d sampler %s spp %u seed %llu randomize %u maxdist %.17g jitter %d dir %u",
                      udm1_version_string(), (unsigned long long)scene_.digest(), a.width, a.height, a.sampler.c_str(),
                      a.spp, (unsigned long long)a.seed, a.randomize, a.max_distance, (int)a.jitter,
                      a.direction_dim);
        return buf;
    }

    udm1app::PartialImage render(const udm1app::RenderSettings &s, udm1app::RenderStats *stats) override
    {
        if (!rt_) rt_ = std::make_unique<udm1scene::EmbreeScene>(scene_);
        udm1ao::Stats st;
        udm1ao::Image img;
        try {
            img = udm1ao::render(scene_, *rt_, options(s), &st);
            rt_->check("rendering");
        } catch (const udm1scene::SceneError &e) {
            throw Error(e.what(), 1);
        } catch (const std::runtime_error &e) {
            throw Error(e.what(), 2);
        }
        rays_ = st.rays;
        stats->seconds = st.seconds;
        stats->columns = {{"rays", std::to_string(st.rays)}};
        img.sums.made_by = describe(s);
        return img.sums;
    }

    void report(const udm1app::RenderSettings &s, const udm1app::PartialImage &img,
                const udm1app::RenderStats &stats) override
    {
        std::printf("sampler %s spp %u samples [%llu, %llu) size %dx%d image %dx%d at %d,%d seconds %.4f rays %llu "
                    "rays_per_second %.4g\n",
                    s.sampler.c_str(), s.spp, (unsigned long long)img.first, (unsigned long long)(img.first + img.count),
                    img.width, img.height, img.full_width, img.full_height, img.x0, img.y0, stats.seconds,
                    (unsigned long long)rays_, rays_ / std::max(stats.seconds, 1e-9));
    }

    std::vector<float> display(const udm1app::PartialImage &img, bool *srgb) const override
    {
        *srgb = false;  // occlusion fractions, stored linear
        return img.rgb();
    }

    bool owns(const udm1app::PartialImage &img) const override { return img.channels == std::vector<std::string>{"A"}; }

    void check_sampler(const std::string &name) const override
    {
        udm1ao::Options a = ao_;
        a.sampler = name;
        try {
            udm1_seq_destroy(udm1ao::make_sampler(a));
        } catch (const std::runtime_error &e) {
            throw Error(e.what(), 2);
        }
    }

    bool pictures_as_output() const override { return true; }

private:
    udm1ao::Options options(const udm1app::RenderSettings &s) const { return udm1app::with_settings(ao_, s); }

    Defaults defaults_{"udm1-ao", USAGE, "ao.png", "episwr", 64, "sobol-owen", 8192, 1u << 20, {}};
    udm1ao::Options ao_;
    udm1scene::Scene scene_;
    std::unique_ptr<udm1scene::EmbreeScene> rt_;
    uint64_t rays_ = 0;
};

}  // namespace

int main(int argc, char **argv) { return udm1app::renderer_main<AoRenderer>(argc, argv); }
