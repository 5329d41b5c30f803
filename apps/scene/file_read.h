// file_read.h - reading a whole scene or mesh file, refusing what is not a regular file, and inflating
// gzip-compressed ones as pbrt-v4 does (a name ending in .gz).
#pragma once

#include <string>

namespace udm1scene {

// The bytes of the regular file at path. Throws SceneError "path: <what> ..." if it cannot be opened or is
// not a regular file (a folder, a device such as /dev/zero, a FIFO: reading those would never end).
std::string read_regular_file(const std::string &path, const std::string &what);

// Whether pbrt-v4 reads the file as gzip-compressed: its name ends in ".gz", in any case.
bool is_gzip_name(const std::string &path);

// read_regular_file, then, if the name ends in ".gz", the bytes inflated (every gzip member of the file,
// through zlib). A file so named that is not complete, valid gzip data is refused: "path: <what> is not
// valid gzip data (...)".
std::string read_scene_file(const std::string &path, const std::string &what);

}  // namespace udm1scene
