// sampler.h - a render's sampler from its command-line name: the one set-up both renderers use.
#pragma once

#include <udm1/seq.h>

#include <cstdint>
#include <memory>
#include <string>

namespace udm1app {

// Preset `name` with `dims` dimensions, K = spp for point sets, seed and randomization as given (the
// screen randomization spread over the whole render's spp, so that sample ranges merge). A preset with
// fewer dimensions gets its own count (but at least 2, a pixel's) when `clip` (the rest is padded), else std::runtime_error saying
// that `who` needs `dims`. An unknown name or a bad combination: std::runtime_error with udm1's message.
// Release with udm1_seq_destroy.
udm1_seq *create_render_sampler(const std::string &name, uint32_t dims, bool clip, uint32_t spp, uint64_t seed,
                                uint32_t randomize, const std::string &who);

// The same sampler, shared: the last one made is kept and given again to a call with the same arguments, so
// that the renders of one image's sample ranges in one process (--checkpoints: each prefix's new samples) set
// it up once (a screen-randomized one searches its screen generators). Thread-safe.
std::shared_ptr<const udm1_seq> shared_render_sampler(const std::string &name, uint32_t dims, bool clip, uint32_t spp,
                                                      uint64_t seed, uint32_t randomize, const std::string &who);

}  // namespace udm1app
