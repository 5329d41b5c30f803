// partial_image.h - the images udm1-pt and udm1-ao write with -o IMAGE.exr: exact per-pixel
// sums of the samples over a range of sample indices [first, first + count) and a window of
// pixels (a tile), in one OpenEXR file. Its R, G, B channels show the mean (any viewer opens
// it); the 32-bit integer channels sum.<C>.hi and sum.<C>.lo hold the fixed-point sums of each
// summed channel C; attributes record what made it (the render without range and window), the
// whole render's spp, the range, the scale and the counts of non-finite and clamped values.
// The window is the file's data window inside the whole image (its display window).
//
// Because the sums are integers, images of disjoint ranges and tiles of one render merge
// exactly: any split merged gives the whole render bit for bit (merge_partials).
#pragma once

#include "udm1app/atomic_file.h"

#include <cstdint>
#include <string>
#include <vector>

namespace udm1app {

struct PartialImage {
    std::string made_by;                        // udm1:render - equal for every part of one render
    uint64_t spp = 0;                           // the whole render's samples per pixel
    uint64_t first = 0, count = 0;              // the sample indices summed: [first, first + count)
    int full_width = 0, full_height = 0;        // the whole image
    int x0 = 0, y0 = 0, width = 0, height = 0;  // the window held: [x0, x0 + width) x [y0, y0 + height)
    std::vector<std::string> channels;          // the summed channels: {"R", "G", "B"}, {"A"}, or with a last
                                                // channel "W": the samples' weights (a pixel filter's, signed)
    double scale = 1;                           // a sample value v is summed as llround(v * scale)
    std::vector<int64_t> sum;                   // channels.size() per window pixel, row-major
    uint64_t nonfinite = 0, clamped = 0;        // sample values left out / clamped

    // An empty image of `channels` over the window, sums zero.
    void reset(int full_w, int full_h, int wx0, int wy0, int w, int h, std::vector<std::string> names, double s);
    // Per window pixel and shown channel (all but W): sum / (scale * count); weighted, the weighted mean sum / W.
    std::vector<float> mean() const;
    std::vector<float> rgb() const;   // the mean as RGB (one channel shown as grey)
    bool weighted() const;            // whether the last channel is the weights' sum W
    size_t shown() const;             // the channels mean() gives: all but W
    bool whole() const { return x0 == 0 && y0 == 0 && width == full_width && height == full_height; }
};

// Write atomically (no partial file on failure); throws Error naming the path. zip: compressed (OpenEXR's zip),
// else uncompressed.
void write_partial(const std::string &path, const PartialImage &p, bool zip = true);
// Write into `file`, left for the caller to commit with the run's other outputs.
void write_partial(AtomicFile &file, const PartialImage &p, bool zip = true);
// Read; throws Error naming the path (unreadable, or not such an image).
PartialImage read_partial(const std::string &path);
// Add parts of one render: the same description and spp; sorted by range, every pixel of the
// parts' bounding window must receive one contiguous range of sample indices, the same for all
// pixels (tiles may differ in how their range is split). Throws Error naming the offending file.
PartialImage merge_partials(const std::vector<std::string> &paths);

// Whether a path names an OpenEXR file (.exr, any case): the only format that keeps the sums.
bool is_exr_path(const std::string &path);

// "--pixel-bounds X0,Y0,X1,Y1" (pbrt's order: the window [X0, X1) x [Y0, Y1)); checked against the
// image size later (check_pixel_bounds). Throws Error naming the flag.
void parse_pixel_bounds(const std::string &text, const std::string &flag, int bounds[4]);
// Resolve bounds (all zero: the whole image) against a width x height image; throws Error.
void check_pixel_bounds(int bounds[4], int width, int height);

}  // namespace udm1app
