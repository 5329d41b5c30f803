// cli.cpp - see cli.h.
#include "udm1app/cli.h"

#include <udm1/udm1.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace udm1app {

uint64_t parse_u64(const std::string &text, const std::string &what, uint64_t lo, uint64_t hi)
{
    const char *s = text.c_str();
    char *end = nullptr;
    errno = 0;
    unsigned long long v = std::strtoull(s, &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE || text[0] == '-' || v < lo || v > hi)
        throw Error(what + " '" + quote_raw(text) + "' is not a whole number in " + std::to_string(lo) + ".." +
                    std::to_string(hi));
    return v;
}

double parse_double(const std::string &text, const std::string &what, double lo, double hi)
{
    const char *s = text.c_str();
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(s, &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v) || v < lo || v > hi)
        throw Error(what + " '" + quote_raw(text) + "' is not a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                    "]");
    return v;
}

uint32_t parse_randomize(const std::string &text)
{
    if (text == "none") return UDM1_RANDOMIZE_NONE;
    if (text == "default") return UDM1_RANDOMIZE_DEFAULT;
    if (text == "shift") return UDM1_RANDOMIZE_SHIFT;
    if (text == "permute") return UDM1_RANDOMIZE_PERMUTE;
    if (text == "owen") return UDM1_RANDOMIZE_OWEN;
    if (text == "screen") return UDM1_RANDOMIZE_SCREEN;
    if (text == "screen-fixed") return RANDOMIZE_SCREEN_FIXED;
    throw Error("--randomize '" + quote_raw(text) + "' is not one of none, default, shift, permute, owen, screen, screen-fixed");
}

bool parse_exr_compression(const std::string &text)
{
    if (text == "zip") return true;
    if (text == "none") return false;
    throw Error("--exr-compression '" + quote_raw(text) + "' is not one of zip, none");
}

std::vector<std::string> parse_list(const std::string &text, const std::string &flag)
{
    std::vector<std::string> parts;
    size_t start = 0;
    for (;;) {
        size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (parts.back().empty()) throw Error(flag + " '" + quote_raw(text, 80) + "' has an empty item");
        if (comma == std::string::npos) return parts;
        start = comma + 1;
    }
}

void parse_size(const std::string &text, const std::string &flag, int max_side, uint64_t max_pixels, int *width,
                int *height)
{
    size_t x = text.find('x');
    if (x == std::string::npos) throw Error(flag + " '" + quote_raw(text) + "' is not WxH");
    int w = 0, h = 0;
    try {
        w = (int)parse_u64(text.substr(0, x), flag, 1, (uint64_t)max_side);
        h = (int)parse_u64(text.substr(x + 1), flag, 1, (uint64_t)max_side);
    } catch (const Error &) {  // name the whole input, not the half that failed
        throw Error(flag + " '" + quote_raw(text) + "' is not WxH with sides in 1.." + std::to_string(max_side), 2);
    }
    if ((uint64_t)w * h > max_pixels)
        throw Error(flag + " '" + quote_raw(text) + "' has more than " + std::to_string(max_pixels) + " pixels");
    *width = w, *height = h;
}

}  // namespace udm1app
