// sampler.cpp - a render's sampler from its command-line name (sampler.h).
#include "udm1app/sampler.h"

#include "udm1app/cli.h"
#include "udm1app/pixel_order.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>

namespace udm1app {

udm1_seq *create_render_sampler(const std::string &name, uint32_t dims, bool clip, uint32_t spp, uint64_t seed,
                                uint32_t randomize, const std::string &who)
{
    udm1_preset_info info;
    if (udm1_preset_find(name.c_str(), &info) != UDM1_OK)
        throw std::runtime_error("unknown sampler '" + name + "' (udm1-seq list shows them)");
    if (!clip && info.max_dimensions < dims)
        throw std::runtime_error("sampler '" + name + "' has " + std::to_string(info.max_dimensions) +
                                 " dimension(s); " + who + " needs " + std::to_string(dims));
    udm1_seq_desc desc;
    udm1_seq_desc_init(&desc);
    desc.preset = name.c_str();
    desc.dimensions = clip ? std::max(2u, std::min(dims, info.max_dimensions)) : dims;  // a pixel takes 2
    desc.point_count = (info.flags & UDM1_PRESET_POINT_SET) ? spp : 0;
    desc.seed = seed;
    desc.randomize = randomize;
    if (randomize == RANDOMIZE_SCREEN_FIXED) {  // the whole render's spp: ranges merge
        desc.randomize = UDM1_RANDOMIZE_SCREEN;
        desc.screen_spp = spp;
    } else if (randomize == UDM1_RANDOMIZE_SCREEN && zorder_sampler(name)) {
        desc.randomize = UDM1_RANDOMIZE_DEFAULT;  // Z-order: one stream, its own scrambling (pixel_order.h)
    }
    udm1_seq *seq = nullptr;
    if (udm1_seq_create_desc(&desc, &seq) != UDM1_OK) throw std::runtime_error(udm1_last_error());
    return seq;
}

std::shared_ptr<const udm1_seq> shared_render_sampler(const std::string &name, uint32_t dims, bool clip, uint32_t spp,
                                                      uint64_t seed, uint32_t randomize, const std::string &who)
{
    static std::mutex mutex;
    static std::string last_key;
    static std::shared_ptr<const udm1_seq> last;
    const std::string key = name + '\n' + std::to_string(dims) + ' ' + std::to_string(clip) + ' ' + std::to_string(spp) +
                            ' ' + std::to_string(seed) + ' ' + std::to_string(randomize);
    std::lock_guard<std::mutex> lock(mutex);
    if (!last || key != last_key) {
        last.reset(create_render_sampler(name, dims, clip, spp, seed, randomize, who),
                   [](const udm1_seq *seq) { udm1_seq_destroy(const_cast<udm1_seq *>(seq)); });
        last_key = key;
    }
    return last;
}

}  // namespace udm1app
