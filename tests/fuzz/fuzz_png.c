/* fuzz_png.c - libFuzzer target: the PNG bridge (png_bridge.c, linked in rather
 * than loaded, so that it is instrumented).  Any input must decode or fail with
 * a message; never crash, leak or hang.  A decoded 8-bit image re-encoded must
 * decode to the same values. */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "io/codec_bridge.h"
#include "textura.h"

extern const struct tex_codec_bridge tex_png_bridge;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const struct tex_codec_bridge *br = &tex_png_bridge;
    char err[400];
    int w, h, nc;
    float *px;

    if (br->info(data, size, &w, &h, &nc, err, sizeof err) < 0)
        return 0;
    if (w < 1 || h < 1 || nc < 1 || nc > 4)
        abort();
    if ((size_t)w * h > (1u << 20)) /* keep each run short; the limits are tested elsewhere */
        return 0;
    if (!(px = malloc(sizeof *px * w * h * nc)))
        return 0;
    if (br->read(data, size, px, err, sizeof err) == 0) {
        size_t n = (size_t)w * h * nc;
        unsigned char *q = malloc(n);
        int fd = memfd_create("fuzz", 0);
        tex_buf b = {0};
        for (size_t i = 0; q && i < n; i++)
            q[i] = (unsigned char)(px[i] * 255.0f + 0.5f);
        if (q && fd >= 0 && br->write(fd, q, w, h, nc, 8, err, sizeof err) == 0 &&
            lseek(fd, 0, SEEK_SET) == 0 && tex_read_fd(fd, &b, "out") == 0) {
            float *r = malloc(sizeof *r * n);
            int w2, h2, nc2;
            if (!r || br->info(b.data, b.len, &w2, &h2, &nc2, err, sizeof err) < 0 || w2 != w ||
                h2 != h || nc2 != nc || br->read(b.data, b.len, r, err, sizeof err) < 0)
                abort();
            for (size_t i = 0; i < n; i++)
                if (r[i] != (float)q[i] / 255.0f)
                    abort();
            free(r);
        }
        tex_buf_free(&b);
        if (fd >= 0)
            close(fd);
        free(q);
    }
    free(px);
    return 0;
}
