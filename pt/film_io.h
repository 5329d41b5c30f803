// film_io.h - udm1-pt's images on disk: an OpenEXR file whose R, G, B channels are
// the mean radiance and whose six 32-bit integer channels sum.R.hi ... sum.B.lo hold
// the exact fixed-point sums, with the sample range and what made the image as
// attributes. Ranges of the same render merge exactly (merge_partials).
#pragma once

#include "integrator.h"

#include <string>

namespace udm1pt {

struct Partial {
    Accumulator acc;
    std::string made_by;  // the render's description without the range (udm1:render)
    uint64_t spp = 0;     // the whole render's spp (udm1:spp)
};

// Write atomically (no partial file on failure); throws udm1app::Error naming the path.
void write_partial(const std::string &path, const Partial &p);
// Read; throws udm1app::Error naming the path (not an udm1-pt image, unreadable).
Partial read_partial(const std::string &path);
// Add ranges of one render: same description, size and spp, disjoint ranges that together form
// one contiguous range. Throws udm1app::Error naming the offending file.
Partial merge_partials(const std::vector<std::string> &paths);

}  // namespace udm1pt
