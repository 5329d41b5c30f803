// partial_image.cpp - see partial_image.h.
#include "udm1app/partial_image.h"

#include "exr_file.h"
#include "udm1app/atomic_file.h"
#include "udm1app/cli.h"
#include "udm1app/image_read.h"
#include "udm1app/image_write.h"


#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace udm1app {

void PartialImage::reset(int full_w, int full_h, int wx0, int wy0, int w, int h, std::vector<std::string> names, double s)
{
    full_width = full_w, full_height = full_h, x0 = wx0, y0 = wy0, width = w, height = h;
    channels = std::move(names);
    scale = s;
    sum.assign((size_t)w * h * channels.size(), 0);
}

bool PartialImage::weighted() const { return channels.size() > 1 && channels.back() == "W"; }

size_t PartialImage::shown() const { return weighted() ? channels.size() - 1 : channels.size(); }

std::vector<float> PartialImage::mean() const
{
    const size_t nsum = channels.size(), nshow = shown(), npix = nsum ? sum.size() / nsum : 0;
    std::vector<float> out(npix * nshow);
    const double d = count ? scale * (double)count : 1.0;  // count 0: sums are 0
    for (size_t i = 0; i < npix; ++i) {
        const int64_t *s = &sum[i * nsum];
        // weighted: sum / W (W 0: no weight, 0 as pbrt-v4's film leaves such a pixel)
        const double w = weighted() ? (double)s[nshow] : d;
        for (size_t c = 0; c < nshow; ++c) out[i * nshow + c] = w != 0 ? (float)((double)s[c] / w) : 0.0f;
    }
    return out;
}

std::vector<float> PartialImage::rgb() const
{
    std::vector<float> m = mean();
    const size_t nshow = shown();
    if (nshow == 3) return m;
    std::vector<float> out(3 * m.size() / nshow);
    for (size_t i = 0; i < out.size(); ++i) out[i] = m[(i / 3) * nshow];
    return out;
}

void write_partial(AtomicFile &file, const PartialImage &p, bool zip)
{
    const std::string &path = file.path();
    if (image_extension(path) != "exr")
        throw Error("cannot write '" + path + "': images with exact sums are OpenEXR (.exr)", 2);
    const size_t nsum = p.channels.size();
    ExrImage exr;
    exr.full_width = p.full_width, exr.full_height = p.full_height;
    exr.x0 = p.x0, exr.y0 = p.y0, exr.width = p.width, exr.height = p.height;
    exr.channels = {{"R", false}, {"G", false}, {"B", false}};
    for (const std::string &c : p.channels)
        for (const char *half : {".hi", ".lo"}) exr.channels.push_back({"sum." + c + half, true});
    exr.attributes["Software"] = "udm1";
    exr.attributes["udm1:render"] = p.made_by;
    std::string names;
    for (const std::string &c : p.channels) names += (names.empty() ? "" : ",") + c;
    exr.attributes["udm1:channels"] = names;  // OpenEXR sorts channels by name: keep their order here
    exr.attributes["udm1:spp"] = std::to_string(p.spp);
    exr.attributes["udm1:first"] = std::to_string(p.first);
    exr.attributes["udm1:count"] = std::to_string(p.count);
    char scale[40];
    std::snprintf(scale, sizeof scale, "%.17g", p.scale);
    exr.attributes["udm1:scale"] = scale;
    exr.attributes["udm1:nonfinite"] = std::to_string(p.nonfinite);
    exr.attributes["udm1:clamped"] = std::to_string(p.clamped);
    const size_t nc = exr.channels.size(), npix = (size_t)p.width * p.height;
    std::vector<float> shown = p.rgb();
    exr.pixels.resize(npix * nc);
    for (size_t i = 0; i < npix; ++i) {
        uint32_t *px = &exr.pixels[i * nc];
        std::memcpy(px, &shown[3 * i], 3 * sizeof(float));
        for (size_t c = 0; c < nsum; ++c) {
            const uint64_t v = (uint64_t)p.sum[nsum * i + c];
            px[3 + 2 * c] = (uint32_t)(v >> 32), px[4 + 2 * c] = (uint32_t)v;
        }
    }
    exr.zip = zip;
    std::vector<unsigned char> bytes = encode_exr(exr, path);
    file.write(bytes.data(), bytes.size());
}

void write_partial(const std::string &path, const PartialImage &p, bool zip)
{
    AtomicFile file(path);
    write_partial(file, p, zip);
    file.commit();
}

PartialImage read_partial(const std::string &path)
{
    const std::string not_ours = "'" + path + "' is not an udm1 image with exact sums";
    if (!is_exr_file(path)) throw Error(not_ours, 2);
    ExrImage exr = decode_exr(path);
    auto attribute = [&](const char *name) {
        auto at = exr.attributes.find(name);
        return at == exr.attributes.end() ? std::string() : at->second;
    };
    auto channel = [&](const std::string &name) {
        for (size_t c = 0; c < exr.channels.size(); ++c)
            if (exr.channels[c].name == name) return (int)c;
        return -1;
    };
    PartialImage p;
    p.made_by = attribute("udm1:render");
    if (p.made_by.empty()) throw Error(not_ours, 2);
    // OpenEXR keeps channels in name order: find the summed ones by name, in the order written
    std::vector<int> where;
    std::string names = attribute("udm1:channels");
    for (size_t at = 0; !names.empty() && at <= names.size();) {
        size_t comma = std::min(names.find(',', at), names.size());
        std::string name = names.substr(at, comma - at);
        int hi = channel("sum." + name + ".hi"), lo = channel("sum." + name + ".lo");
        if (name.empty() || hi < 0 || lo < 0 || !exr.channels[hi].uint || !exr.channels[lo].uint) throw Error(not_ours, 2);
        p.channels.push_back(name);
        where.push_back(hi), where.push_back(lo);
        at = comma + 1;
    }
    if (p.channels.empty()) throw Error(not_ours, 2);
    auto number = [&](const char *name) -> uint64_t {
        std::string s = attribute(name);
        char *end = nullptr;
        unsigned long long v = std::strtoull(s.c_str(), &end, 10);
        if (s.empty() || *end) throw Error("'" + path + "': bad attribute " + name, 2);
        return v;
    };
    p.spp = number("udm1:spp"), p.first = number("udm1:first"), p.count = number("udm1:count");
    p.nonfinite = number("udm1:nonfinite"), p.clamped = number("udm1:clamped");
    std::string scale = attribute("udm1:scale");
    char *end = nullptr;
    p.scale = std::strtod(scale.c_str(), &end);
    if (scale.empty() || *end || !(p.scale > 0) || !std::isfinite(p.scale)) throw Error("'" + path + "': bad attribute udm1:scale", 2);
    if (p.count == 0 || p.first + p.count > p.spp || p.first + p.count < p.first)
        throw Error("'" + path + "': the sample range does not fit udm1:spp", 2);
    p.x0 = exr.x0, p.y0 = exr.y0, p.width = exr.width, p.height = exr.height;
    p.full_width = exr.full_width, p.full_height = exr.full_height;
    if (exr.full_x0 != 0 || exr.full_y0 != 0 || p.x0 < 0 || p.y0 < 0 || p.width <= 0 || p.height <= 0 || (int64_t)p.x0 + p.width > p.full_width ||
        (int64_t)p.y0 + p.height > p.full_height)
        throw Error("'" + path + "': its data window is not inside its display window", 2);
    const size_t nc = exr.channels.size(), nsum = p.channels.size();
    p.sum.resize((size_t)p.width * p.height * nsum);
    for (size_t i = 0; i < (size_t)p.width * p.height; ++i)
        for (size_t c = 0; c < nsum; ++c) {
            const uint64_t hi = exr.pixels[i * nc + (size_t)where[2 * c]], lo = exr.pixels[i * nc + (size_t)where[2 * c + 1]];
            p.sum[nsum * i + c] = (int64_t)((hi << 32) | lo);
        }
    return p;
}

PartialImage merge_partials(const std::vector<std::string> &paths)
{
    if (paths.empty()) throw Error("merge needs at least one image", 2);
    std::vector<PartialImage> parts;
    for (const std::string &p : paths) parts.push_back(read_partial(p));
    const PartialImage &a = parts[0];
    int bx0 = a.x0, by0 = a.y0, bx1 = a.x0 + a.width, by1 = a.y0 + a.height;
    for (size_t k = 1; k < parts.size(); ++k) {
        const PartialImage &p = parts[k];
        if (p.made_by != a.made_by || p.spp != a.spp || p.channels != a.channels || p.scale != a.scale ||
            p.full_width != a.full_width || p.full_height != a.full_height)
            throw Error("'" + paths[k] + "' is from another render than '" + paths[0] + "'", 2);
        bx0 = std::min(bx0, p.x0), by0 = std::min(by0, p.y0);
        bx1 = std::max(bx1, p.x0 + p.width), by1 = std::max(by1, p.y0 + p.height);
    }
    std::vector<size_t> order(parts.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return parts[x].first < parts[y].first; });
    PartialImage out;
    out.made_by = a.made_by, out.spp = a.spp;
    out.reset(a.full_width, a.full_height, bx0, by0, bx1 - bx0, by1 - by0, a.channels, a.scale);
    const size_t nsum = a.channels.size(), npix = (size_t)out.width * out.height;
    const uint64_t unset = std::numeric_limits<uint64_t>::max();
    std::vector<uint64_t> start(npix, unset), next(npix, unset);  // each pixel's range so far
    for (size_t k : order) {
        const PartialImage &p = parts[k];
        for (int y = 0; y < p.height; ++y)
            for (int x = 0; x < p.width; ++x) {
                size_t i = (size_t)(p.y0 + y - by0) * out.width + (p.x0 + x - bx0);
                if (start[i] == unset) start[i] = next[i] = p.first;
                if (next[i] != p.first)
                    throw Error("'" + paths[k] + "' gives pixel (" + std::to_string(p.x0 + x) + ", " +
                                    std::to_string(p.y0 + y) + ") samples from " + std::to_string(p.first) +
                                    " on, the files before it end there at " + std::to_string(next[i]) +
                                    " (ranges must be disjoint and contiguous)",
                                2);
                next[i] = p.first + p.count;
                const int64_t *src = &p.sum[nsum * ((size_t)y * p.width + x)];
                for (size_t c = 0; c < nsum; ++c) out.sum[nsum * i + c] += src[c];
            }
        out.nonfinite += p.nonfinite, out.clamped += p.clamped;
    }
    for (size_t i = 0; i < npix; ++i)
        if (start[i] != start[0] || next[i] != next[0]) {
            int x = bx0 + (int)(i % out.width), y = by0 + (int)(i / out.width);
            std::string has = start[i] == unset ? "no samples"
                                                : "samples [" + std::to_string(start[i]) + ", " + std::to_string(next[i]) + ")";
            throw Error("the images do not cover their window evenly: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") has " + has + ", pixel (" + std::to_string(bx0) + ", " + std::to_string(by0) + ") samples [" +
                            std::to_string(start[0]) + ", " + std::to_string(next[0]) + ")",
                        2);
        }
    out.first = start[0], out.count = next[0] - start[0];
    return out;
}

bool is_exr_path(const std::string &path)
{
    std::string lower = path;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return (char)std::tolower(c); });
    return lower.size() >= 4 && lower.compare(lower.size() - 4, 4, ".exr") == 0;
}

void parse_pixel_bounds(const std::string &text, const std::string &flag, int bounds[4])
{
    std::vector<std::string> parts = parse_list(text, flag);
    if (parts.size() != 4) throw Error(flag + " '" + text + "' is not X0,Y0,X1,Y1");
    for (int k = 0; k < 4; ++k) bounds[k] = (int)parse_u64(parts[k], flag, 0, 1u << 20);
    if (bounds[2] <= bounds[0] || bounds[3] <= bounds[1])
        throw Error(flag + " '" + text + "' is an empty window (X1 must exceed X0 and Y1 exceed Y0)");
}

void check_pixel_bounds(int bounds[4], int width, int height)
{
    if (bounds[0] == 0 && bounds[1] == 0 && bounds[2] == 0 && bounds[3] == 0) {
        bounds[2] = width, bounds[3] = height;
        return;
    }
    if (bounds[2] > width || bounds[3] > height)
        throw Error("--pixel-bounds " + std::to_string(bounds[0]) + "," + std::to_string(bounds[1]) + "," +
                        std::to_string(bounds[2]) + "," + std::to_string(bounds[3]) + " is not inside the " +
                        std::to_string(width) + "x" + std::to_string(height) + " image",
                    2);
}

}  // namespace udm1app
