// stderr_capture.h - what a library prints on stderr by itself (libpng's "libpng error: ..." lines,
// printed before OpenImageIO reports the same error), caught around the call so that a tool can fold it
// into its one-line error instead of letting it reach the user as lines of its own.
#pragma once

#include <string>

namespace udm1app {

// While it lives, file descriptor 2 goes to an anonymous in-memory file (every thread's writes, the C and
// C++ streams' and raw write(2)s alike). take() ends the capture and returns the text; if take() is never
// called (the call succeeded, or another exception left the scope), the destructor ends the capture and
// hands the text on to stderr unchanged, so a library's warning on success is printed as it always was.
// Where the capture cannot be set up, it captures nothing and stderr is left as it is.
class StderrCapture {
public:
    StderrCapture();
    ~StderrCapture();
    StderrCapture(const StderrCapture &) = delete;
    StderrCapture &operator=(const StderrCapture &) = delete;

    std::string take();

private:
    int saved_ = -1, file_ = -1;
};

}  // namespace udm1app
