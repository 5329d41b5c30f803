// image_calls.cpp - see image_calls.h.
#include "image_calls.h"

#include "udm1app/cli.h"
#include "udm1app/image_read.h"
#include "udm1app/one_line.h"
#include "udm1app/stderr_capture.h"

#include <OpenImageIO/filesystem.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

namespace udm1app {

namespace {

// The Error of a failed call: what OpenImageIO queued and what the codec printed, as one line.
[[noreturn]] void fail(const char *verb, const std::string &path, const std::string &queued, const std::string &printed,
                       const char *no_reason)
{
    std::string why = fold_lines(queued + "\n" + printed);
    throw Error(std::string("cannot ") + verb + " '" + path + "': " + (why.empty() ? no_reason : why), 1);
}

const char *const READ_NO_REASON = "the file is damaged or cut short (OpenImageIO gives no reason)";

// A PNG file's chunks, checked to run whole up to IEND before libpng reads it: OpenImageIO 2.4's PNG reader
// leaks its message when libpng's read hits the end of the file, so a cut PNG is refused here. "" if whole
// (or not a PNG), else what is wrong.
std::string png_cut_short(const std::string &path)
{
    std::ifstream f(path, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    static const char SIGNATURE[] = "\x89PNG\r\n\x1a\n";
    if (data.compare(0, 8, SIGNATURE, 8) != 0) return "";
    auto u32 = [&](size_t at) {
        return ((uint32_t)(unsigned char)data[at] << 24) | ((uint32_t)(unsigned char)data[at + 1] << 16) |
               ((uint32_t)(unsigned char)data[at + 2] << 8) | (uint32_t)(unsigned char)data[at + 3];
    };
    for (size_t at = 8;;) {
        if (data.size() - at < 8)
            return "cut short: the file ends at byte " + std::to_string(data.size()) + ", with no IEND chunk";
        const uint64_t length = u32(at);
        const std::string type = data.substr(at + 4, 4);
        if (length > 0x7FFFFFFFu || data.size() - at < length + 12)
            return "cut short: chunk '" + quote_raw(type) + "' at byte " + std::to_string(at) + " holds " +
                   std::to_string(length) + " bytes, the file ends at byte " + std::to_string(data.size());
        if (type == "IEND") return "";
        at += 12 + (size_t)length;
    }
}

}  // namespace

std::unique_ptr<OIIO::ImageInput> open_image(const std::string &path)
{
    require_regular_file(path);
    const std::string cut = png_cut_short(path);
    if (!cut.empty()) throw Error("cannot read '" + path + "': " + cut, 1);
    OIIO::geterror();  // what an earlier call left queued is not this file's
    StderrCapture capture;
    auto in = OIIO::ImageInput::open(path);
    if (!in) fail("read", path, OIIO::geterror(), capture.take(), READ_NO_REASON);
    if (in->has_error()) fail("read", path, in->geterror(), capture.take(), READ_NO_REASON);
    return in;
}

void read_pixels(OIIO::ImageInput &in, const std::string &path, OIIO::TypeDesc type, void *data)
{
    StderrCapture capture;
    const bool ok = in.read_image(0, 0, 0, in.spec().nchannels, type, data);
    if (!ok || in.has_error()) fail("read", path, in.geterror(), capture.take(), READ_NO_REASON);
}

size_t image_values(const OIIO::ImageInput &in, const std::string &path)
{
    const OIIO::ImageSpec &spec = in.spec();
    const uint64_t limit = 1ull << 30;
    const uint64_t values = (uint64_t)spec.width * (uint64_t)spec.height * (uint64_t)spec.depth * (uint64_t)spec.nchannels;
    if (spec.width < 1 || spec.height < 1 || spec.depth < 1 || spec.nchannels < 1)
        throw Error("cannot read '" + path + "': the image has no pixels", 1);
    if (spec.depth > 1 || values > limit)
        throw Error("cannot read '" + path + "': " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        (spec.depth > 1 ? "x" + std::to_string(spec.depth) : std::string()) + " pixels of " +
                        std::to_string(spec.nchannels) + " channels are more than the tools read (2^30 values, 2D)",
                    1);
    return (size_t)values;
}

void encode_image(OIIO::ImageOutput &out, const OIIO::ImageSpec &spec, OIIO::TypeDesc type, const void *data,
                  AtomicFile &file)
{
    // the formats whose writers OpenImageIO 2.4 runs on a memory buffer (its HDR writer crashes there): the
    // others write the temporary file themselves
    const std::string format = out.format_name();
    const bool in_memory = format == "png" || format == "openexr" || format == "tiff" || format == "jpeg" ||
                           format == "bmp" || format == "targa";
    std::vector<unsigned char> bytes;
    {
        OIIO::Filesystem::IOVecOutput memory(bytes);
        OIIO::geterror();
        StderrCapture capture;
        if (in_memory && !out.set_ioproxy(&memory))
            fail("write", file.path(), out.geterror(), capture.take(), "its format cannot be written to memory");
        const std::string target = in_memory ? file.path() : file.temp_path();
        // a writer's message queued on success is not a failure: OpenImageIO 2.4's TIFF writer queues
        // "failed TIFFWriteCustomDirectory() of the Exif data" with every (complete, valid) file
        if (!(out.open(target, spec) && out.write_image(type, data) && out.close())) {
            std::string queued = out.geterror() + "\n" + OIIO::geterror();
            for (size_t at; (at = queued.find(file.temp_path())) != std::string::npos;)  // name the output
                queued.replace(at, file.temp_path().size(), file.path());
            fail("write", file.path(), queued, capture.take(), "OpenImageIO gives no reason");
        }
        out.geterror();
    }
    file.write(bytes.data(), bytes.size());
}

}  // namespace udm1app
