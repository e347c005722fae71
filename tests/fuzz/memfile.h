/* memfile.h - the libFuzzer entry for readers that take a path: the input
 * becomes a memory file, named /proc/self/fd/N, handed to the target's
 *   static void read_path(const char *path);
 * The target defines _GNU_SOURCE before its includes (memfd_create). */
#include <stdint.h>
#include <stdio.h>
#include <sys/mman.h>
#include <unistd.h>

#include "textura.h"

static void read_path(const char *path);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[64];
    int fd = memfd_create("fuzz", 0);

    if (fd < 0)
        return 0;
    if (tex_write_all(fd, data, size, "fuzz") == 0) {
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
        read_path(path);
    }
    close(fd);
    return 0;
}
