/* fuzz_netpbm.c - libFuzzer target: the native PNM, PAM and PFM reader, and ProSim's
 * headerless .r and .pic (prosim.h), their size from the name or the square.
 * Any input must decode or fail with a message; never crash, leak or hang.
 * What decodes as PAM at 16 bits must re-encode and decode to within half a step. */
#define _GNU_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "textura.h"

/* ProSim's files: the first byte picks bytes or floats and a name with or without a size */
static void prosim(const uint8_t *data, size_t size)
{
    static const char *const names[4] = {"fuzz.r", "fuzz_7x3.r", "fuzz.pic", "fuzz_4x2.pic"};
    if (size < 1)
        return;
    int k = data[0] & 3;
    tex_map *m = tex_prosim_decode(data + 1, size - 1, k >= 2, names[k]);
    if (m && (size_t)m->w * m->h * (k >= 2 ? 4 : 1) != size - 1)
        abort(); /* every byte is a sample */
    tex_map_free(m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    tex_map *m = tex_netpbm_decode(data, size, "fuzz");
    int fd;

    prosim(data, size);
    if (!m)
        return 0;
    if ((fd = memfd_create("fuzz", 0)) >= 0) {
        tex_buf b = {0};
        tex_map *r = NULL;
        if (tex_pnm_write_fd(m, fd, 16, TEX_PNM_PAM, "out") == 0 && lseek(fd, 0, SEEK_SET) == 0 &&
            tex_read_fd(fd, &b, "out") == 0)
            r = tex_netpbm_decode(b.data, b.len, "again");
        if (!r || r->w != m->w || r->h != m->h || r->nc != m->nc)
            abort();
        for (size_t i = 0; i < tex_map_samples(m); i++) {
            float v = m->px[i];
            v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN writes as 0 */
            if (fabsf(r->px[i] - v) > 0.5f / 65535 + 1e-6f)
                abort();
        }
        tex_map_free(r);
        tex_buf_free(&b);
        close(fd);
    }
    tex_map_free(m);
    return 0;
}
