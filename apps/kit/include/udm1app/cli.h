// cli.h - command-line helpers shared by udm1's tools: parsing numbers and
// names strictly, and one-line errors that name the bad input.
#pragma once

#include "udm1app/one_line.h"

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

namespace udm1app {

// A user error: the tool prints "<tool>: <message>" and exits with `code`.
struct Error : std::runtime_error {
    int code;
    explicit Error(const std::string &message, int exit_code = 2) : std::runtime_error(message), code(exit_code) {}
};

// The whole string must be a number in [lo, hi]; otherwise Error naming `what`.
uint64_t parse_u64(const std::string &text, const std::string &what, uint64_t lo, uint64_t hi);
double parse_double(const std::string &text, const std::string &what, double lo, double hi);

// An app-level randomization past udm1_randomize: "screen-fixed", the library's screen scheme with the
// render's spp fixed (UDM1_RANDOMIZE_SCREEN with desc.screen_spp = spp); "screen" is the progressive one.
constexpr uint32_t RANDOMIZE_SCREEN_FIXED = 0x100;

// udm1_randomize from "none", "default", "shift", "permute", "owen", "screen", or RANDOMIZE_SCREEN_FIXED
// from "screen-fixed".
uint32_t parse_randomize(const std::string &text);

// --exr-compression: true (zip-compressed) from "zip", false (uncompressed) from "none".
bool parse_exr_compression(const std::string &text);

// "a,b,c" as its items; an empty item is an Error naming `flag`.
std::vector<std::string> parse_list(const std::string &text, const std::string &flag);

// "WxH", each side in 1..max_side and W x H at most max_pixels; otherwise an Error naming `flag`.
void parse_size(const std::string &text, const std::string &flag, int max_side, uint64_t max_pixels, int *width,
                int *height);

// One of a few named choices: the value of the name `text`, else an Error "FLAG 'text' is not a, b or c".
template <class T>
T parse_choice(const std::string &text, const std::string &flag, std::initializer_list<std::pair<const char *, T>> choices)
{
    std::string names;
    size_t k = 0;
    for (const auto &c : choices) {
        if (text == c.first) return c.second;
        names += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(c.first);
        ++k;
    }
    throw Error(flag + " '" + quote_raw(text) + "' is not " + names);
}

// A tool's main: run `body` (returning the exit code); an Error prints "<tool>: <message>" and exits
// with its code, any other exception prints the same and exits 1. The message is printed as one line
// whatever it holds (fold_lines: a library's lines joined, control characters escaped). A file grown past
// the process's size limit is a write error (SIGXFSZ ignored), not a kill that leaves a temporary file.
template <class F> int run_tool(const char *tool, F &&body)
{
    std::signal(SIGXFSZ, SIG_IGN);
    try {
        return body();
    } catch (const Error &e) {
        std::fprintf(stderr, "%s: %s\n", tool, fold_lines(e.what()).c_str());
        return e.code;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s: %s\n", tool, fold_lines(e.what()).c_str());
        return 1;
    }
}

}  // namespace udm1app
