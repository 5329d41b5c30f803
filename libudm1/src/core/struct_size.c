/* struct_size.c - the descriptors' size protocol: a struct_size field first, layouts that only append. */
#include "core/internal.h"

#include <string.h>

udm1_status udm1_read_struct(const char *fn, const char *what, const char *init_fn, const void *src,
                             size_t v1_size, void *dst, size_t dst_size)
{
    uint32_t size;
    memcpy(&size, src, sizeof size);
    if (size < v1_size)
        return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT, "%s: %s.struct_size %u is below the first layout's %zu (call %s)",
                         fn, what, size, v1_size, init_fn);
    const unsigned char *bytes = src;
    for (size_t at = dst_size; at < size; ++at)
        if (bytes[at] != 0)
            return udm1_fail(UDM1_ERROR_INVALID_ARGUMENT,
                             "%s: %s.struct_size %u: byte %zu, past the %zu bytes this udm1 %s knows, is set (a field "
                             "of a newer udm1)", fn, what, size, at, dst_size, udm1_version_string());
    size_t n = size < dst_size ? size : dst_size;
    memcpy(dst, src, n);
    memset((unsigned char *)dst + n, 0, dst_size - n);
    return UDM1_OK;
}
