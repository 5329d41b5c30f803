// atomic_file.cpp - see atomic_file.h.
#include "udm1app/atomic_file.h"

#include "udm1app/cli.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <unistd.h>

namespace udm1app {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path))
{
    size_t slash = path_.find_last_of('/');
    std::string dir = slash == std::string::npos ? "." : path_.substr(0, slash + 1);
    std::string base = slash == std::string::npos ? path_ : path_.substr(slash + 1);
    if (base.empty()) throw Error("output path '" + path_ + "' names a folder, not a file", 1);
    if (access(dir.c_str(), W_OK) != 0)
        throw Error("cannot write '" + path_ + "': " + std::strerror(errno), 1);
    size_t dot = base.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : base.substr(dot);
    std::random_device rd;
    char tag[24];
    std::snprintf(tag, sizeof tag, "%08x", static_cast<unsigned>(rd()));
    temp_ = (slash == std::string::npos ? "" : dir) + "." + base + ".tmp" + tag + ext;
}

AtomicFile::~AtomicFile()
{
    if (!committed_) std::remove(temp_.c_str());
}

void AtomicFile::commit()
{
    if (std::rename(temp_.c_str(), path_.c_str()) != 0)
        throw Error("cannot write '" + path_ + "': " + std::strerror(errno), 1);
    committed_ = true;
}

}  // namespace udm1app
