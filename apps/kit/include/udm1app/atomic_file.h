// atomic_file.h - write an output file under a temporary name in the same
// folder and rename it into place on success, so that a failed or interrupted
// run never leaves a partial file behind.
#pragma once

#include <string>

namespace udm1app {

class AtomicFile {
public:
    // Picks a temporary name beside `path` that keeps its extension (image
    // writers choose the format by it). Throws Error if the folder is not
    // writable.
    explicit AtomicFile(std::string path);
    ~AtomicFile();  // removes the temporary file unless commit() succeeded
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    const std::string &temp_path() const { return temp_; }
    const std::string &path() const { return path_; }
    void commit();  // rename the temporary file to the final path; throws Error

private:
    std::string path_, temp_;
    bool committed_ = false;
};

}  // namespace udm1app
