// one_line.cpp - see one_line.h.
#include "udm1app/one_line.h"

#include <cctype>
#include <cstdio>
#include <cstring>
#include <vector>

namespace udm1app {

namespace {

// The length of the well-formed UTF-8 sequence at s[i] (1 to 4), or 0 if none starts there (a stray
// continuation byte, an overlong form, a surrogate, a code point above U+10FFFF, a cut sequence).
size_t utf8_length(const std::string &s, size_t i)
{
    auto cont = [&](size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) {
        if (i + k >= s.size()) return false;
        unsigned b = (unsigned char)s[i + k];
        return b >= lo && b <= hi;
    };
    unsigned b = (unsigned char)s[i];
    if (b < 0x80) return 1;
    if (b >= 0xC2 && b <= 0xDF) return cont(1) ? 2 : 0;
    if (b >= 0xE0 && b <= 0xEF) {
        unsigned lo = b == 0xE0 ? 0xA0 : 0x80, hi = b == 0xED ? 0x9F : 0xBF;
        return cont(1, lo, hi) && cont(2) ? 3 : 0;
    }
    if (b >= 0xF0 && b <= 0xF4) {
        unsigned lo = b == 0xF0 ? 0x90 : 0x80, hi = b == 0xF4 ? 0x8F : 0xBF;
        return cont(1, lo, hi) && cont(2) && cont(3) ? 4 : 0;
    }
    return 0;
}

// The character at s[i] as printable() writes it; *used is the number of bytes it took.
std::string printable_char(const std::string &s, size_t i, size_t *used)
{
    char buf[16];
    size_t n = utf8_length(s, i);
    unsigned b = (unsigned char)s[i];
    *used = n ? n : 1;
    if (n == 0) {  // not UTF-8: the byte itself
        std::snprintf(buf, sizeof buf, "\\x%02X", b);
        return buf;
    }
    if (n == 1) {
        if (b == '\t') return "\\t";
        if (b == '\n') return "\\n";
        if (b == '\r') return "\\r";
        if (b < 0x20 || b == 0x7F) {
            std::snprintf(buf, sizeof buf, "\\x%02X", b);
            return buf;
        }
        return std::string(1, (char)b);
    }
    unsigned cp = 0;  // C1 controls (U+0080..U+009F) and U+2028, U+2029 end a line for some readers
    if (n == 2) cp = ((b & 0x1Fu) << 6) | ((unsigned char)s[i + 1] & 0x3Fu);
    if (n == 3) cp = ((b & 0x0Fu) << 12) | (((unsigned char)s[i + 1] & 0x3Fu) << 6) | ((unsigned char)s[i + 2] & 0x3Fu);
    if ((cp >= 0x80 && cp <= 0x9F) || cp == 0x2028 || cp == 0x2029) {
        std::snprintf(buf, sizeof buf, "\\u%04X", cp);
        return buf;
    }
    return s.substr(i, n);
}

// Whether `needle` occurs in `hay` as a phrase: not starting or ending inside a word of it ("b" is not in
// "Embree: a").
bool has_phrase(const std::string &hay, const std::string &needle)
{
    auto word = [](char c) { return std::isalnum((unsigned char)c) || c == '_'; };
    for (size_t at = hay.find(needle); at != std::string::npos; at = hay.find(needle, at + 1)) {
        size_t end = at + needle.size();
        if ((at == 0 || !word(hay[at - 1]) || !word(needle.front())) &&
            (end == hay.size() || !word(hay[end]) || !word(needle.back())))
            return true;
    }
    return false;
}

std::string trim(const std::string &s)
{
    size_t a = s.find_first_not_of(" \t\r\f\v"), b = s.find_last_not_of(" \t\r\f\v");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// A line as another line may already say it: without a leading library tag ending in "error" or
// "warning" ("libpng error: IHDR: CRC error" is said by "PNG read error: IHDR: CRC error").
std::string untagged(const std::string &line)
{
    size_t colon = line.find(": ");
    if (colon == std::string::npos || line.size() - (colon + 2) < 8) return line;
    std::string tag = line.substr(0, colon);
    for (char &c : tag) c = (char)std::tolower((unsigned char)c);
    auto ends_with = [&](const char *w) {
        size_t n = std::strlen(w);
        return tag.size() >= n && tag.compare(tag.size() - n, n, w) == 0;
    };
    return ends_with("error") || ends_with("warning") ? line.substr(colon + 2) : line;
}

}  // namespace

std::string printable(const std::string &text)
{
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0, used = 0; i < text.size(); i += used) out += printable_char(text, i, &used);
    return out;
}

std::string fold_lines(const std::string &text)
{
    std::vector<std::string> lines;
    for (size_t at = 0; at <= text.size();) {
        size_t nl = text.find('\n', at);
        if (nl == std::string::npos) nl = text.size();
        std::string line = trim(text.substr(at, nl - at));
        if (!line.empty()) lines.push_back(line);
        at = nl + 1;
    }
    // a line that another one contains, whole or without its tag, says nothing new: leave it out (of two
    // lines that say the same, the first stays: a library's queued message before what a codec printed)
    std::vector<bool> keep(lines.size(), true);
    for (size_t i = lines.size(); i-- > 0;)
        for (size_t j = 0; j < lines.size() && keep[i]; ++j) {
            if (i == j || !keep[j]) continue;
            const std::string &other = lines[j];
            bool same = lines[i] == other;
            if ((same && j < i) || (!same && (has_phrase(other, lines[i]) || has_phrase(other, untagged(lines[i])))))
                keep[i] = false;
        }
    std::string out;
    for (size_t i = 0; i < lines.size(); ++i)
        if (keep[i]) out += (out.empty() ? "" : "; ") + lines[i];
    return printable(out);
}

std::string quote_raw(const std::string &text, size_t max_chars)
{
    size_t end = text.size();
    while (end > 0 && (text[end - 1] == '\n' || text[end - 1] == '\r')) --end;  // the line end
    std::string out;
    size_t chars = 0;
    for (size_t i = 0, used = 0; i < end; i += used, ++chars) {
        if (chars == max_chars) return out + "...";
        out += printable_char(text, i, &used);
    }
    return out;
}

}  // namespace udm1app
