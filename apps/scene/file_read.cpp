// file_read.cpp - see file_read.h.
#include "file_read.h"

#include "scene.h"

#include <sys/stat.h>

#include <fstream>
#include <sstream>

namespace udm1scene {

std::string read_regular_file(const std::string &path, const std::string &what)
{
    struct stat st;
    if (stat(path.c_str(), &st) != 0) throw SceneError(path + ": cannot open the " + what);
    if (!S_ISREG(st.st_mode)) throw SceneError(path + ": the " + what + " is not a regular file");
    std::ifstream f(path, std::ios::binary);
    if (!f) throw SceneError(path + ": cannot open the " + what);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace udm1scene
