/* codec.h - the libFuzzer entry for a codec bridge (codec_bridge.h), linked in rather than
 * loaded so that it is instrumented: the target defines
 *   #define BRIDGE tex_tiff_bridge     and     #define EXACT 1 (a lossless format) or 0
 * before including it.  Any input must decode or fail with a message; never crash, leak or
 * hang.  What decodes is written again as 8 bits and must decode to the same size and
 * channels, and, for a lossless format, to the same values. */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "io/codec_bridge.h"
#include "textura.h"

extern const struct tex_codec_bridge BRIDGE;

/* q (w x h x nc bytes) written by br and read back, checked against it */
static void again(const struct tex_codec_bridge *br, const unsigned char *q, int w, int h, int nc)
{
    char err[400];
    int fd = memfd_create("fuzz", 0), w2, h2, nc2;
    tex_buf b = {0};
    if (fd >= 0 && br->write(fd, q, w, h, nc, 8, err, sizeof err) == 0 &&
        lseek(fd, 0, SEEK_SET) == 0 && tex_read_fd(fd, &b, "out") == 0) {
        size_t n = (size_t)w * h * nc;
        float *r = malloc(sizeof *r * n);
        if (!r || br->info(b.data, b.len, &w2, &h2, &nc2, err, sizeof err) < 0 || w2 != w ||
            h2 != h || nc2 != nc || br->read(b.data, b.len, r, err, sizeof err) < 0)
            abort();
        for (size_t i = 0; EXACT && i < n; i++)
            if (r[i] != (float)q[i] / 255.0f)
                abort();
        free(r);
    }
    tex_buf_free(&b);
    if (fd >= 0)
        close(fd);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const struct tex_codec_bridge *br = &BRIDGE;
    char err[400];
    int w, h, nc;

    if (br->info(data, size, &w, &h, &nc, err, sizeof err) < 0)
        return 0;
    if (w < 1 || h < 1 || nc < 1)
        abort();
    nc = nc < 4 ? nc : 4; /* read gives the first four */
    if ((size_t)w * h > (1u << 20)) /* keep each run short; the limits are tested elsewhere */
        return 0;
    size_t n = (size_t)w * h * nc;
    float *px = malloc(sizeof *px * n);
    unsigned char *q = malloc(n);
    if (px && q && br->read(data, size, px, err, sizeof err) == 0) {
        for (size_t i = 0; i < n; i++) {
            float v = px[i] > 0 ? (px[i] < 1 ? px[i] : 1) : 0; /* a float TIFF's NaN: 0 */
            q[i] = (unsigned char)(v * 255.0f + 0.5f);
        }
        if (EXACT || nc == 1 || nc == 3) /* JPEG writes grey and RGB */
            again(br, q, w, h, nc);
    }
    free(q);
    free(px);
    return 0;
}
