// file_read.h - reading a whole scene or mesh file, refusing what is not a regular file.
#pragma once

#include <string>

namespace udm1scene {

// The bytes of the regular file at path. Throws SceneError "path: <what> ..." if it cannot be opened or is
// not a regular file (a folder, a device such as /dev/zero, a FIFO: reading those would never end).
std::string read_regular_file(const std::string &path, const std::string &what);

}  // namespace udm1scene
