// one_line.h - text made fit for the one line of a tool's error message: what a library says (which may
// span several lines) folded into one, and raw input quoted so that it cannot break or garble the line.
#pragma once

#include <cstddef>
#include <string>

namespace udm1app {

// `text` with every character that would end or move a terminal line, or that is not UTF-8, escaped: tab,
// CR and LF as \t, \r, \n; the other C0 controls, DEL and bytes that do not form UTF-8 as \xNN; the C1
// controls and the Unicode line and paragraph separators as \uNNNN. Valid UTF-8 otherwise passes through.
std::string printable(const std::string &text);

// A library's message (OpenImageIO's error queue, what a codec printed on stderr, Embree's message) as one
// line: its lines trimmed, the empty ones and those another line already says left out, the rest joined
// with "; ", then printable().
std::string fold_lines(const std::string &text);

// Raw input (a token, a line of a file) as it is quoted in a message: without its line end, printable(),
// and cut after about `max_chars` characters with "..." after the cut.
std::string quote_raw(const std::string &text, size_t max_chars = 40);

}  // namespace udm1app
