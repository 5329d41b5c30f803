// regular_file.cpp - require_regular_file (udm1app/image_read.h): apart, so that the OpenImageIO module
// (oiio_module.h) has it without the kit's readers.
#include "udm1app/cli.h"
#include "udm1app/image_read.h"

#include <sys/stat.h>

namespace udm1app {

void require_regular_file(const std::string &path)
{
    struct stat st;
    if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) throw Error("cannot read '" + path + "': not a regular file", 1);
}

}  // namespace udm1app
