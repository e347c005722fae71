/* memfile.h - for fuzz targets of readers that take a path: the input as a
 * memory file, named /proc/self/fd/N in path.  Returns its descriptor (close
 * it), or -1.  The target defines _GNU_SOURCE before its includes (memfd_create). */
#include <stdint.h>
#include <stdio.h>
#include <sys/mman.h>
#include <unistd.h>

#include "textura.h"

static int memfile(const uint8_t *data, size_t size, char *path, size_t n)
{
    int fd = memfd_create("fuzz", 0);

    if (fd < 0)
        return -1;
    if (tex_write_all(fd, data, size, "fuzz") < 0) {
        close(fd);
        return -1;
    }
    snprintf(path, n, "/proc/self/fd/%d", fd);
    return fd;
}
