// atomic_file.h - write an output file under a temporary name in the same
// folder and rename it into place on success, so that a failed run never
// leaves a partial file behind (not even the temporary one).
#pragma once

#include <string>
#include <vector>

namespace udm1app {

class AtomicFile {
public:
    // Creates the temporary file beside `path` at once, so that an output that
    // cannot be written (a missing or read-only folder, a path that names a
    // folder or a device) fails here, before any work. Throws Error naming `path`.
    explicit AtomicFile(std::string path);
    ~AtomicFile();  // removes the temporary file unless commit() succeeded
    AtomicFile(AtomicFile &&other) noexcept;
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;
    AtomicFile &operator=(AtomicFile &&) = delete;

    const std::string &path() const { return path_; }
    // The temporary file, for a writer that opens it by name (what it writes there is committed too).
    const std::string &temp_path() const { return temp_; }
    // Append bytes to the temporary file; throws Error "cannot write 'path': <errno text>".
    void write(const void *data, size_t size);
    void write(const std::string &bytes) { write(bytes.data(), bytes.size()); }
    // Close the temporary file, checking that every byte reached it; throws Error. commit() calls it.
    void finish();
    void commit();  // finish(), then rename the temporary file to the final path; throws Error

private:
    std::string path_, temp_;
    int fd_ = -1;
    bool committed_ = false;
};

// Commit several outputs of one run: every file finished first, then renamed, so that a write error in
// any of them leaves none in place.
void commit_all(std::vector<AtomicFile> &files);

}  // namespace udm1app
