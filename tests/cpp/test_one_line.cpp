// test_one_line.cpp - the tools' one-line errors: library text folded into one line, raw input quoted
// printable and short, stderr captured around a library call (every way of writing to it, from any
// thread), a tool's error printed as one line whatever it holds, and Embree's errors caught by its
// error function (never printed by Embree) and reported as one line naming the scene.
#include "../c/check.h"

#include "builtin.h"
#include "embree_scene.h"
#include "udm1app/cli.h"
#include "udm1app/one_line.h"
#include "udm1app/stderr_capture.h"

#include <cstring>
#include <iostream>
#include <string>
#include <thread>
#include <unistd.h>

using udm1app::fold_lines;
using udm1app::printable;
using udm1app::quote_raw;

// No byte of s ends or moves a line, and s is ASCII (what printable() writes for these inputs).
static bool one_plain_line(const std::string &s)
{
    for (unsigned char c : s)
        if (c < 0x20 || c >= 0x7F) return false;
    return true;
}

static void test_printable()
{
    CHECK(printable("plain text: 1.5") == "plain text: 1.5");
    CHECK(printable("a\tb\r\nc") == "a\\tb\\r\\nc");
    CHECK(printable(std::string("nul\0x", 5)) == "nul\\x00x");
    CHECK(printable("\x1b[31mred\x7f") == "\\x1B[31mred\\x7F");
    CHECK(printable("\x0b\x0c\x1c\x1d\x1e") == "\\x0B\\x0C\\x1C\\x1D\\x1E");  // line breaks to some readers
    CHECK(printable("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x99\x82") == "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x99\x82");  // UTF-8 stays
    CHECK(printable("\xc2\x85|\xe2\x80\xa8|\xe2\x80\xa9") == "\\u0085|\\u2028|\\u2029");  // NEL, LS, PS
    CHECK(printable("\xff\xfe") == "\\xFF\\xFE");
    CHECK(printable("\xc0\xaf") == "\\xC0\\xAF");          // overlong '/'
    CHECK(printable("\xed\xa0\x80") == "\\xED\\xA0\\x80");  // a surrogate
    CHECK(printable("\xf4\x90\x80\x80") == "\\xF4\\x90\\x80\\x80");  // above U+10FFFF
    CHECK(printable("\xe2\x82") == "\\xE2\\x82");          // cut short
    CHECK(printable(std::string("\x1f\x8b\x08\x00", 4)) == "\\x1F\\x8B\\x08\\x00");  // a gzip header
}

static void test_fold_lines()
{
    // OpenImageIO's queue after a cut PNG, then what libpng printed itself: said once, in one line
    std::string queued = "Read error: hit end of file\nPNG read error: IDAT: Read error: hit end of file\nPNG library error";
    std::string printed = "libpng error: IDAT: Read error: hit end of file\n";
    std::string f = fold_lines(queued + "\n" + printed);
    CHECKF(f == "PNG read error: IDAT: Read error: hit end of file; PNG library error", "%s", f.c_str());
    f = fold_lines("PNG read error: IHDR: CRC error\nlibpng error: IHDR: CRC error\n");
    CHECKF(f == "PNG read error: IHDR: CRC error", "%s", f.c_str());
    CHECK(fold_lines("") == "");
    CHECK(fold_lines("\n \r\n\t\n") == "");
    CHECK(fold_lines("  one  \r\n\r\ntwo\n") == "one; two");
    CHECK(fold_lines("same\nsame\nsame") == "same");
    CHECK(fold_lines("a: short\nb: short") == "a: short; b: short");  // tags that are not errors are kept
    CHECK(fold_lines("line\rcarriage\x1b") == "line\\rcarriage\\x1B");  // a lone CR is not a line break here
    f = fold_lines("Embree: a\nb\n\nc");
    CHECK(f == "Embree: a; b; c" && one_plain_line(f));
}

static void test_quote_raw()
{
    CHECK(quote_raw("Shape \"sphere\"\n") == "Shape \"sphere\"");  // without its line end
    CHECK(quote_raw("word\r\n") == "word");
    CHECK(quote_raw("a\rb\tc") == "a\\rb\\tc");
    CHECK(quote_raw("0123456789", 4) == "0123...");
    CHECK(quote_raw("0123", 4) == "0123");
    CHECK(quote_raw("\x01\x02\x03", 2) == "\\x01\\x02...");  // cut between characters, never inside an escape
    CHECK(quote_raw("\xc3\xa9\xc3\xa9\xc3\xa9", 2) == "\xc3\xa9\xc3\xa9...");  // nor inside a UTF-8 character
    std::string long_binary(100000, '\x8b');
    std::string q = quote_raw(long_binary);
    CHECKF(q.size() < 200 && one_plain_line(q), "%zu bytes", q.size());
}

static void test_stderr_capture()
{
    std::string text;
    {
        udm1app::StderrCapture capture;
        std::fprintf(stderr, "stdio\n");
        std::cerr << "iostream" << std::endl;
        std::clog << "clog\n";
        ssize_t n = write(2, "raw\n", 4);
        (void)n;
        std::thread t([] { std::fputs("thread\n", stderr); });
        t.join();
        text = capture.take();
    }
    CHECKF(text == "stdio\niostream\nclog\nraw\nthread\n", "%s", text.c_str());
    // not taken: handed on to the stderr outside (here an outer capture), unchanged
    std::string outer_text, inner_text;
    {
        udm1app::StderrCapture outer;
        {
            udm1app::StderrCapture inner;
            std::fprintf(stderr, "libpng warning: kept\n");
        }
        {
            udm1app::StderrCapture inner;
            std::fprintf(stderr, "taken\n");
            inner_text = inner.take();
        }
        std::fprintf(stderr, "after\n");
        outer_text = outer.take();
    }
    CHECKF(outer_text == "libpng warning: kept\nafter\n", "%s", outer_text.c_str());
    CHECK(inner_text == "taken\n");
}

static void test_run_tool_prints_one_line()
{
    std::string text;
    int code = 0;
    {
        udm1app::StderrCapture capture;
        code = udm1app::run_tool("udm1-test", [] () -> int {
            throw udm1app::Error("cannot read 'x.png': first\nsecond\r\n\x1b[2J", 1);
        });
        code += 10 * udm1app::run_tool("udm1-test", [] () -> int { throw std::runtime_error("multi\nline"); });
        text = capture.take();
    }
    CHECKF(code == 11, "%d", code);
    CHECKF(text == "udm1-test: cannot read 'x.png': first; second; \\x1B[2J\nudm1-test: multi; line\n", "%s", text.c_str());
}

static void test_embree_errors()
{
    udm1scene::Scene scene = udm1scene::builtin_scene("cornell");
    scene.source = "cornell.pbrt";
    udm1scene::EmbreeScene rt(scene);
    rt.check("building");  // no error so far: no throw
    std::string printed, message;
    {
        udm1app::StderrCapture capture;
        rtcSetSceneBuildQuality(rt.handle(), (RTCBuildQuality)99);  // Embree refuses it through its error function
        printed = capture.take();
    }
    CHECKF(printed.empty(), "Embree printed '%s'", printed.c_str());
    try {
        rt.check("rendering");
    } catch (const udm1scene::SceneError &e) {
        message = e.what();
    }
    CHECKF(message.rfind("cornell.pbrt: Embree failed while rendering: RTC_ERROR_", 0) == 0 &&
               message.find("build quality") != std::string::npos &&
               one_plain_line(message),
           "'%s'", message.c_str());
}

int main()
{
    test_printable();
    test_fold_lines();
    test_quote_raw();
    test_stderr_capture();
    test_run_tool_prints_one_line();
    test_embree_errors();
    CHECK_DONE();
}
