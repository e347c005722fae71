/* test_planes.c - a scanline's channel runs joined into pixels and pixels split into runs,
 * at every SIMD level: each sample where it belongs, for widths that fill the lanes and leave
 * tails; and the EXR stream's bytes laid out as OpenEXR lays them (each channel's run, in the
 * order of the channels' names), read back to the same pixels */
#include <stdlib.h>
#include <string.h>

#include "base/simd.h"
#include "io/planes.h"
#include "textura.h"
#include "unit.h"

enum { W = 41 };

static void test_moves(void)
{
    static const size_t widths[] = {0, 1, 7, 8, 9, 16, 23, W};
    float runs[4][W], px[4 * W], back[4][W];
    for (int k = 0; k < 4; k++)
        for (int x = 0; x < W; x++)
            runs[k][x] = (float)(k * 1000 + x) + 0.5f;
    for (int level = tex_simd_level(); level >= TEX_SIMD_SCALAR; level--) {
        int joined = 1, split = 1;
        tex_simd_limit(level);
        for (int nc = 1; nc <= 4; nc++)
            for (size_t i = 0; i < sizeof widths / sizeof *widths; i++) {
                size_t w = widths[i];
                const float *plane[4] = {runs[0], runs[1], runs[2], runs[3]};
                float *out[4] = {back[0], back[1], back[2], back[3]};
                memset(px, 0xff, sizeof px);
                memset(back, 0xff, sizeof back);
                tex_planes_join(px, plane, nc, w);
                for (size_t x = 0; x < w; x++)
                    for (int k = 0; k < nc; k++)
                        joined &= px[x * nc + k] == runs[k][x];
                for (size_t j = w * nc; j < 4 * W; j++) /* nothing written past the row */
                    joined &= px[j] != px[j];
                tex_planes_split(out, px, nc, w);
                for (int k = 0; k < nc; k++)
                    for (int x = 0; x < W; x++)
                        split &= (size_t)x < w ? back[k][x] == runs[k][x]
                                               : back[k][x] != back[k][x];
            }
        CHECKF(joined, "level %d: runs joined into pixels, each sample where it belongs", level);
        CHECKF(split, "level %d: pixels split into runs, each sample where it belongs", level);
    }
    tex_simd_limit(TEX_SIMD_AVX512);
}

/* A one-row stream, uncompressed: its last bytes are the row's chunk, the channels' runs in
 * the order of their names (B G R, A B G R), as the core's own pack lays them */
static void test_layout(void)
{
    static const char *names[4][4] = {{"Y"}, {"G", "R"}, {"B", "G", "R"}, {"A", "B", "G", "R"}};
    for (int level = tex_simd_level(); level >= TEX_SIMD_SCALAR; level--) {
        tex_simd_limit(level);
        for (int nc = 1; nc <= 4; nc++) {
            tex_map *m = tex_map_new(W, 1, nc), *r;
            tex_buf b = {0};
            int laid = 1;
            for (int x = 0; x < W; x++)
                for (int k = 0; k < nc; k++)
                    m->px[x * nc + k] = (float)(x + 100 * k);
            if (tex_exr_encode(m, TEX_COMPRESS_NONE, &b) < 0 || b.len < (size_t)W * nc * 4) {
                CHECKF(0, "level %d: a %d-channel row encoded", level, nc);
                tex_map_free(m);
                continue;
            }
            const unsigned char *run = b.data + b.len - (size_t)W * nc * 4;
            for (int c = 0; c < nc; c++) { /* run c: the channel named names[nc - 1][c] */
                int k = !strcmp(names[nc - 1][c], "A") ? 3 : !strcmp(names[nc - 1][c], "B") ? 2
                        : !strcmp(names[nc - 1][c], "G") ? 1 : 0;
                for (int x = 0; x < W; x++) {
                    float v;
                    memcpy(&v, run + ((size_t)c * W + x) * 4, 4);
                    laid &= v == m->px[x * nc + k];
                }
            }
            CHECKF(laid, "level %d: %d channel(s) laid out in runs by name", level, nc);
            r = tex_exr_decode(b.data, b.len, "the row");
            CHECKF(r && r->nc == nc && !memcmp(r->px, m->px, sizeof(float) * W * nc),
                   "level %d: %d channel(s) read back to the same pixels", level, nc);
            tex_map_free(r);
            tex_map_free(m);
            tex_buf_free(&b);
        }
    }
    tex_simd_limit(TEX_SIMD_AVX512);
}

int main(void)
{
    test_moves();
    test_layout();
    return unit_done();
}
