// oiio_module.cpp - see oiio_module.h.
#include "oiio_module.h"

#include "udm1app/cli.h"

#include <dlfcn.h>

#include <mutex>

namespace udm1app {

const OiioCalls &oiio_calls(const char *verb, const std::string &path)
{
    static std::once_flag once;
    static const OiioCalls *calls = nullptr;
    static std::string why;
    std::call_once(once, [] {
        void *module = dlopen(UDM1_OIIO_MODULE, RTLD_NOW | RTLD_LOCAL);
        const char *error = module ? nullptr : dlerror();
        auto entry = module ? (const OiioCalls *(*)())dlsym(module, "udm1_app_oiio_calls") : nullptr;
        if (!entry) why = error ? error : "it has no udm1_app_oiio_calls";
        else if ((calls = entry())->version != UDM1_OIIO_CALLS_VERSION) calls = nullptr, why = "it is of another build";
    });
    if (!calls)
        throw Error(std::string("cannot ") + verb + " '" + path + "': OpenImageIO's module " UDM1_OIIO_MODULE
                                                                  " cannot be loaded: " + why, 1);
    return *calls;
}

}  // namespace udm1app
