// film_io.cpp - see film_io.h.
#include "film_io.h"

#include "../tools/common/atomic_file.h"
#include "../tools/common/cli.h"

#include "../tools/common/image_read.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>

namespace udm1pt {

using udm1app::Error;

namespace {

const char *SUM_NAMES[6] = {"sum.R.hi", "sum.R.lo", "sum.G.hi", "sum.G.lo", "sum.B.hi", "sum.B.lo"};
const size_t PIXEL_BYTES = 3 * sizeof(float) + 6 * sizeof(uint32_t);

}  // namespace

void write_partial(const std::string &path, const Partial &p)
{
    const Accumulator &a = p.acc;
    udm1app::AtomicFile file(path);
    auto out = OIIO::ImageOutput::create(file.temp_path());
    if (!out || std::string(out->format_name()) != "openexr")
        throw Error("cannot write '" + path + "': udm1-pt images are OpenEXR (.exr)", 2);
    OIIO::ImageSpec spec(a.width, a.height, 9, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B"};
    spec.channelformats.assign(3, OIIO::TypeDesc::FLOAT);
    for (const char *n : SUM_NAMES) spec.channelnames.push_back(n), spec.channelformats.push_back(OIIO::TypeDesc::UINT);
    spec.attribute("compression", "zip");
    spec.attribute("DateTime", "");
    spec.attribute("Software", "udm1");
    spec.attribute("udm1:render", p.made_by);
    spec.attribute("udm1:spp", std::to_string(p.spp));
    spec.attribute("udm1:first", std::to_string(a.first));
    spec.attribute("udm1:count", std::to_string(a.count));
    spec.attribute("udm1:nonfinite", std::to_string(a.nonfinite));
    spec.attribute("udm1:clamped", std::to_string(a.clamped));
    std::vector<float> mean = a.mean();
    std::vector<unsigned char> buf((size_t)a.width * a.height * PIXEL_BYTES);
    for (size_t i = 0; i < (size_t)a.width * a.height; ++i) {
        unsigned char *px = &buf[i * PIXEL_BYTES];
        std::memcpy(px, &mean[3 * i], 3 * sizeof(float));
        for (int c = 0; c < 3; ++c) {
            uint64_t v = (uint64_t)a.sum[3 * i + c];
            uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v;
            std::memcpy(px + 12 + 8 * c, &hi, 4);
            std::memcpy(px + 16 + 8 * c, &lo, 4);
        }
    }
    if (!out->open(file.temp_path(), spec) || !out->write_image(OIIO::TypeDesc::UNKNOWN, buf.data()) || !out->close())
        throw Error("cannot write '" + path + "': " + out->geterror(), 1);
    file.commit();
}

Partial read_partial(const std::string &path)
{
    udm1app::require_regular_file(path);
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read '" + path + "': " + OIIO::geterror(), 1);
    const OIIO::ImageSpec &spec = in->spec();
    // OpenEXR keeps channels in name order: find the sums by name
    int where[6];
    bool ok = spec.channelformats.size() == (size_t)spec.nchannels;
    for (int c = 0; c < 6; ++c) {
        where[c] = spec.channelindex(SUM_NAMES[c]);
        ok = ok && where[c] >= 0 && spec.channelformats[where[c]] == OIIO::TypeDesc::UINT;
    }
    std::string made_by = spec.get_string_attribute("udm1:render");
    if (!ok || made_by.empty()) throw Error("'" + path + "' is not an udm1-pt image (no exact sums)", 2);
    Partial p;
    p.made_by = made_by;
    auto number = [&](const char *name) -> uint64_t {
        std::string s = spec.get_string_attribute(name);
        char *end = nullptr;
        unsigned long long v = std::strtoull(s.c_str(), &end, 10);
        if (s.empty() || *end) throw Error("'" + path + "': bad attribute " + name, 2);
        return v;
    };
    p.spp = number("udm1:spp");
    Accumulator &a = p.acc;
    a.width = spec.width, a.height = spec.height;
    a.first = number("udm1:first"), a.count = number("udm1:count");
    a.nonfinite = number("udm1:nonfinite"), a.clamped = number("udm1:clamped");
    std::vector<size_t> offset(spec.nchannels + 1, 0);  // byte offset of each channel in a native pixel
    for (int c = 0; c < spec.nchannels; ++c) offset[c + 1] = offset[c] + spec.channelformats[c].size();
    size_t pixel_bytes = offset[spec.nchannels];
    std::vector<unsigned char> buf((size_t)a.width * a.height * pixel_bytes);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, buf.data()))
        throw Error("cannot read '" + path + "': " + in->geterror(), 1);
    a.sum.resize((size_t)a.width * a.height * 3);
    for (size_t i = 0; i < (size_t)a.width * a.height; ++i)
        for (int c = 0; c < 3; ++c) {
            uint32_t hi, lo;
            std::memcpy(&hi, &buf[i * pixel_bytes + offset[where[2 * c]]], 4);
            std::memcpy(&lo, &buf[i * pixel_bytes + offset[where[2 * c + 1]]], 4);
            a.sum[3 * i + c] = (int64_t)(((uint64_t)hi << 32) | lo);
        }
    return p;
}

Partial merge_partials(const std::vector<std::string> &paths)
{
    if (paths.empty()) throw Error("merge needs at least one image", 2);
    std::vector<Partial> parts;
    for (const std::string &p : paths) parts.push_back(read_partial(p));
    std::vector<size_t> order(parts.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return parts[a].acc.first < parts[b].acc.first; });
    Partial out = parts[order[0]];
    for (size_t k = 1; k < order.size(); ++k) {
        const Partial &p = parts[order[k]];
        const std::string &name = paths[order[k]];
        if (p.made_by != out.made_by || p.spp != out.spp)
            throw Error("'" + name + "' is from another render than '" + paths[order[0]] + "'", 2);
        if (p.acc.first != out.acc.first + out.acc.count)
            throw Error("'" + name + "' starts at sample " + std::to_string(p.acc.first) + ", not at " +
                            std::to_string(out.acc.first + out.acc.count) + " (ranges must be disjoint and contiguous)",
                        2);
        for (size_t i = 0; i < out.acc.sum.size(); ++i) out.acc.sum[i] += p.acc.sum[i];
        out.acc.count += p.acc.count;
        out.acc.nonfinite += p.acc.nonfinite;
        out.acc.clamped += p.acc.clamped;
    }
    return out;
}

}  // namespace udm1pt
