// exr_file.cpp - see exr_file.h.
#include "exr_file.h"

#include "udm1app/cli.h"
#include "udm1app/image_read.h"
#include "udm1app/one_line.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <new>

namespace udm1app {

namespace {

// An OpenEXR output stream into memory (the caller's AtomicFile writes the bytes, checking every write).
class MemoryStream : public Imf::OStream {
public:
    explicit MemoryStream(const std::string &name) : Imf::OStream(name.c_str()) {}
    void write(const char c[], int n) override
    {
        if (bytes.size() < at + (size_t)n) bytes.resize(at + (size_t)n);
        std::memcpy(bytes.data() + at, c, (size_t)n);
        at += (size_t)n;
    }
    uint64_t tellp() override { return at; }
    void seekp(uint64_t pos) override { at = (size_t)pos; }
    std::vector<unsigned char> bytes;

private:
    size_t at = 0;
};

// The slices of `image`'s pixel array, one per channel, at OpenEXR's addressing (by data-window coordinates).
Imf::FrameBuffer frame_buffer(ExrImage &image)
{
    const size_t nc = image.channels.size(), xs = 4 * nc, ys = xs * (size_t)image.width;
    // the address of pixel (0, 0), outside the array where the data window does not start there: as an integer
    const uintptr_t origin = (uintptr_t)image.pixels.data() - (uintptr_t)image.x0 * xs - (uintptr_t)image.y0 * ys;
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < nc; ++c)
        fb.insert(image.channels[c].name, Imf::Slice(image.channels[c].uint ? Imf::UINT : Imf::FLOAT,
                                                     (char *)(origin + 4 * c), xs, ys));
    return fb;
}

}  // namespace

bool is_exr_file(const std::string &path)
{
    require_regular_file(path);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error("cannot read '" + path + "': " + std::strerror(errno), 1);
    unsigned char magic[4] = {0, 0, 0, 0};
    f.read((char *)magic, 4);
    return f.gcount() == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

std::vector<unsigned char> encode_exr(const ExrImage &image, const std::string &path)
{
    try {
        Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(image.full_width - 1, image.full_height - 1)),
                           Imath::Box2i(Imath::V2i(image.x0, image.y0),
                                        Imath::V2i(image.x0 + image.width - 1, image.y0 + image.height - 1)));
        header.compression() = image.zip ? Imf::ZIP_COMPRESSION : Imf::NO_COMPRESSION;
        for (const ExrChannel &c : image.channels) header.channels().insert(c.name, Imf::Channel(c.uint ? Imf::UINT : Imf::FLOAT));
        for (const auto &kv : image.attributes) header.insert(kv.first, Imf::StringAttribute(kv.second));
        MemoryStream stream(path);
        {
            Imf::OutputFile out(stream, header, 0);
            ExrImage &pixels = const_cast<ExrImage &>(image);  // (OpenEXR's slices take char *; nothing is written)
            out.setFrameBuffer(frame_buffer(pixels));
            out.writePixels(image.height);
        }
        return std::move(stream.bytes);
    } catch (const std::bad_alloc &) {
        throw Error("cannot write '" + path + "': not enough memory", 1);
    } catch (const std::exception &e) {
        throw Error("cannot write '" + path + "': " + fold_lines(e.what()), 1);
    }
}

ExrImage decode_exr(const std::string &path)
{
    require_regular_file(path);
    ExrImage image;
    try {
        Imf::InputFile in(path.c_str(), 0);
        const Imf::Header &h = in.header();
        const Imath::Box2i data = h.dataWindow(), display = h.displayWindow();
        image.full_x0 = display.min.x, image.full_y0 = display.min.y;
        image.full_width = display.max.x - display.min.x + 1, image.full_height = display.max.y - display.min.y + 1;
        image.x0 = data.min.x, image.y0 = data.min.y;
        const int64_t w = (int64_t)data.max.x - data.min.x + 1, hgt = (int64_t)data.max.y - data.min.y + 1;
        std::vector<ExrChannel> first, rest;
        bool all_half = true;
        for (Imf::ChannelList::ConstIterator i = h.channels().begin(); i != h.channels().end(); ++i) {
            if (i.channel().xSampling != 1 || i.channel().ySampling != 1)
                throw Error("cannot read '" + path + "': channel '" + i.name() + "' is subsampled", 1);
            ExrChannel c{i.name(), i.channel().type == Imf::UINT};
            all_half = all_half && i.channel().type == Imf::HALF;
            (c.name == "R" || c.name == "G" || c.name == "B" || c.name == "A" ? first : rest).push_back(c);
        }
        auto rank = [](const ExrChannel &c) { return std::string("RGBA").find(c.name[0]); };
        std::sort(first.begin(), first.end(), [&](const ExrChannel &a, const ExrChannel &b) { return rank(a) < rank(b); });
        image.channels = first;
        image.channels.insert(image.channels.end(), rest.begin(), rest.end());
        const uint64_t values = (uint64_t)w * (uint64_t)hgt * image.channels.size();
        if (w < 1 || hgt < 1 || image.channels.empty()) throw Error("cannot read '" + path + "': the image has no pixels", 1);
        if (values > (1ull << 30))
            throw Error("cannot read '" + path + "': " + std::to_string(w) + "x" + std::to_string(hgt) + " pixels of " +
                            std::to_string(image.channels.size()) +
                            " channels are more than the tools read (2^30 values, 2D)",
                        1);
        image.width = (int)w, image.height = (int)hgt;
        image.bits = all_half ? 16 : 32;
        for (Imf::Header::ConstIterator a = h.begin(); a != h.end(); ++a)
            if (const auto *s = dynamic_cast<const Imf::StringAttribute *>(&a.attribute())) image.attributes[a.name()] = s->value();
        image.pixels.assign((size_t)values, 0);
        in.setFrameBuffer(frame_buffer(image));
        in.readPixels(data.min.y, data.max.y);
    } catch (const Error &) {
        throw;
    } catch (const std::bad_alloc &) {
        throw Error("cannot read '" + path + "': not enough memory for its pixels", 1);
    } catch (const std::exception &e) {
        throw Error("cannot read '" + path + "': " + fold_lines(e.what()), 1);
    }
    return image;
}

}  // namespace udm1app
