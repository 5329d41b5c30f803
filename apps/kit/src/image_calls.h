// image_calls.h - OpenImageIO's reading and writing calls with their errors made one line, for the kit's
// image files (image_read.cpp, image_write.cpp, partial_image.cpp):
// - each call's error queue is read after a success too: some readers return true with an error queued
//   (a truncated TIFF or JPEG reads as success, the missing rows left black);
// - what a codec prints on stderr by itself (libpng's "libpng error: ...") is captured around the call;
// - both are folded into one Error "cannot read 'FILE': ..." / "cannot write 'FILE': ...";
// - writers encode into memory, and AtomicFile writes the bytes, checking every write (a codec that
//   ignores a failed write, as OpenImageIO's PNG writer does, cannot leave a cut file); the formats whose
//   writers cannot run on memory write the temporary file themselves.
#pragma once

#include "udm1app/atomic_file.h"

#include <OpenImageIO/imageio.h>

#include <memory>
#include <string>

namespace udm1app {

// The image file at `path` opened for reading; throws Error if it cannot be (not a regular file, no
// reader for it, a damaged header).
std::unique_ptr<OIIO::ImageInput> open_image(const std::string &path);

// Every channel of `in`'s first subimage as `type` into `data` (spec().image_pixels() x nchannels
// values, or the native pixel layout with TypeDesc::UNKNOWN); throws Error naming `path`.
void read_pixels(OIIO::ImageInput &in, const std::string &path, OIIO::TypeDesc type, void *data);

// The number of values `in` holds (pixels x channels); throws Error naming `path` if it is more than the
// tools read (2^30 values, a 16384 x 16384 RGBA image).
size_t image_values(const OIIO::ImageInput &in, const std::string &path);

// `data` (spec's pixels, passed as `type`) encoded in the format `out` writes, into `file`; throws Error
// naming file.path().
void encode_image(OIIO::ImageOutput &out, const OIIO::ImageSpec &spec, OIIO::TypeDesc type, const void *data,
                  AtomicFile &file);

}  // namespace udm1app
