/* fuzz_stream.c - libFuzzer target: format sniffing and the EXR stream decoder.
 * Any input must decode or fail with a message; never crash, leak or hang. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    tex_map *m;

    (void)tex_format_sniff(data, size);
    if ((m = tex_exr_decode(data, size, "fuzz"))) {
        /* What decodes must re-encode and decode to the same bits. */
        tex_buf b = {0};
        if (tex_exr_encode(m, TEX_COMPRESS_NONE, &b) == 0) {
            tex_map *r = tex_exr_decode(b.data, b.len, "again");
            if (!r || r->w != m->w || r->h != m->h || r->nc != m->nc ||
                memcmp(r->px, m->px, tex_map_samples(m) * sizeof(float)) != 0)
                abort();
            tex_map_free(r);
        }
        tex_buf_free(&b);
        tex_map_free(m);
    }
    return 0;
}
