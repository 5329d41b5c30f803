// file_read.cpp - see file_read.h.
#include "file_read.h"

#include "scene.h"

#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace udm1scene {

std::string read_regular_file(const std::string &path, const std::string &what)
{
    struct stat st;
    if (stat(path.c_str(), &st) != 0) throw SceneError(path + ": cannot open the " + what);
    if (!S_ISREG(st.st_mode)) throw SceneError(path + ": the " + what + " is not a regular file");
    std::ifstream f(path, std::ios::binary);
    if (!f) throw SceneError(path + ": cannot open the " + what);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

bool is_gzip_name(const std::string &path)
{
    size_t n = path.size();
    return n > 3 && path[n - 3] == '.' && std::tolower((unsigned char)path[n - 2]) == 'g' &&
           std::tolower((unsigned char)path[n - 1]) == 'z';
}

namespace {

// All members of the gzip data in `in`, inflated; throws with zlib's reason.
std::string gunzip(const std::string &in, const std::string &path, const std::string &what)
{
    auto bad = [&](const std::string &why) {
        return SceneError(path + ": the " + what + " is not valid gzip data (" + why + ")");
    };
    if (in.size() < 2 || (unsigned char)in[0] != 0x1f || (unsigned char)in[1] != 0x8b) throw bad("no gzip header");
    std::string out;
    z_stream z{};
    if (inflateInit2(&z, 15 + 16) != Z_OK) throw bad("zlib could not start");  // 15 + 16: gzip framing only
    std::string chunk(1 << 16, '\0');
    size_t fed = 0;  // bytes of `in` handed to zlib so far (zlib counts in uInt: at most 1 GiB at a time)
    try {
        for (;;) {
            if (z.avail_in == 0 && fed < in.size()) {
                z.next_in = (Bytef *)(in.data() + fed);
                z.avail_in = (uInt)std::min<size_t>(in.size() - fed, (size_t)1 << 30);
                fed += z.avail_in;
            }
            z.next_out = (Bytef *)&chunk[0];
            z.avail_out = (uInt)chunk.size();
            int rc = inflate(&z, Z_NO_FLUSH);
            out.append(chunk.data(), chunk.size() - z.avail_out);
            if (rc == Z_STREAM_END) {  // a member ends; another may follow, as gzip itself reads them
                size_t next = fed - z.avail_in;
                if (next == in.size()) break;
                if (in.size() - next < 2 || (unsigned char)in[next] != 0x1f || (unsigned char)in[next + 1] != 0x8b)
                    throw bad("data after the end of the compressed stream");
                inflateReset(&z);
            } else if (rc == Z_BUF_ERROR) {  // no progress: the input is used up
                if (z.avail_in == 0 && fed == in.size()) throw bad("truncated: the compressed data ends early");
            } else if (rc != Z_OK) {
                throw bad(z.msg ? z.msg : "corrupt data");
            }
        }
    } catch (...) {
        inflateEnd(&z);
        throw;
    }
    inflateEnd(&z);
    return out;
}

}  // namespace

std::string read_scene_file(const std::string &path, const std::string &what)
{
    std::string bytes = read_regular_file(path, what);
    return is_gzip_name(path) ? gunzip(bytes, path, what) : bytes;
}

}  // namespace udm1scene
