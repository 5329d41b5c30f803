// stderr_capture.cpp - see stderr_capture.h.
#include "udm1app/stderr_capture.h"

#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <iostream>
#include <sys/mman.h>
#include <unistd.h>

namespace udm1app {

namespace {

void flush_streams()
{
    std::cerr.flush();
    std::clog.flush();
    std::fflush(stderr);
}

void write_all(int fd, const std::string &text)
{
    for (size_t done = 0; done < text.size();) {
        ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        done += (size_t)n;
    }
}

}  // namespace

StderrCapture::StderrCapture()
{
    flush_streams();
    file_ = memfd_create("udm1-stderr", MFD_CLOEXEC);
    if (file_ < 0) return;
    saved_ = fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (saved_ < 0 || dup2(file_, 2) < 0) {
        if (saved_ >= 0) close(saved_);
        close(file_);
        saved_ = file_ = -1;
    }
}

std::string StderrCapture::take()
{
    std::string text;
    if (file_ < 0) return text;
    flush_streams();
    while (dup2(saved_, 2) < 0 && errno == EINTR) {
    }
    close(saved_);
    off_t size = lseek(file_, 0, SEEK_END);
    if (size > 0) {
        text.resize((size_t)size);
        size_t done = 0;
        while (done < text.size()) {
            ssize_t n = pread(file_, &text[done], text.size() - done, (off_t)done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            done += (size_t)n;
        }
        text.resize(done);
    }
    close(file_);
    saved_ = file_ = -1;
    return text;
}

StderrCapture::~StderrCapture()
{
    if (file_ < 0) return;
    std::string text = take();
    write_all(2, text);
}

}  // namespace udm1app
