// atomic_file.cpp - see atomic_file.h.
#include "udm1app/atomic_file.h"

#include "udm1app/cli.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <random>
#include <sys/stat.h>
#include <unistd.h>

namespace udm1app {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path))
{
    size_t slash = path_.find_last_of('/');
    std::string dir = slash == std::string::npos ? "" : path_.substr(0, slash + 1);
    std::string base = slash == std::string::npos ? path_ : path_.substr(slash + 1);
    struct stat st;
    const bool exists = stat(path_.c_str(), &st) == 0;
    if (base.empty() || base == "." || base == ".." || (exists && S_ISDIR(st.st_mode)))
        throw Error("output path '" + path_ + "' names a folder, not a file", 1);
    if (exists && !S_ISREG(st.st_mode))  // a device or FIFO: the rename would replace it
        throw Error("cannot write '" + path_ + "': not a regular file", 1);
    size_t dot = base.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : base.substr(dot);
    std::random_device rd;
    for (int attempt = 0; fd_ < 0; ++attempt) {
        char tag[24];
        std::snprintf(tag, sizeof tag, "%08x", static_cast<unsigned>(rd()));
        temp_ = dir + "." + base + ".tmp" + tag + ext;
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ < 0 && (errno != EEXIST || attempt == 16))
            throw Error("cannot write '" + path_ + "': " + std::strerror(errno), 1);
    }
}

AtomicFile::AtomicFile(AtomicFile &&other) noexcept
    : path_(std::move(other.path_)), temp_(std::move(other.temp_)), fd_(other.fd_), committed_(other.committed_)
{
    other.fd_ = -1;
    other.committed_ = true;  // the moved-from object owns no temporary file
}

AtomicFile::~AtomicFile()
{
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) std::remove(temp_.c_str());
}

void AtomicFile::write(const void *data, size_t size)
{
    if (fd_ < 0) throw Error("cannot write '" + path_ + "': written after it was closed", 1);
    const char *p = static_cast<const char *>(data);
    while (size > 0) {
        ssize_t n = ::write(fd_, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw Error("cannot write '" + path_ + "': " + std::strerror(n < 0 ? errno : EIO), 1);
        p += n;
        size -= (size_t)n;
    }
}

void AtomicFile::finish()
{
    if (fd_ < 0) return;
    int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) throw Error("cannot write '" + path_ + "': " + std::strerror(errno), 1);
}

void AtomicFile::commit()
{
    finish();
    if (std::rename(temp_.c_str(), path_.c_str()) != 0)
        throw Error("cannot write '" + path_ + "': " + std::strerror(errno), 1);
    committed_ = true;
}

void commit_all(std::vector<AtomicFile> &files)
{
    for (AtomicFile &f : files) f.finish();
    for (AtomicFile &f : files) f.commit();
}

}  // namespace udm1app
