/* planes.c - a scanline's channel runs and a map's pixels, moved from one to the other */
#include <string.h>

#include "base/simd.h"
#include "io/planes.h"
#include "io/x86/planes_x86.h"

/* Sample k of pixel x (px[x nc + k]) and plane[k][x], x < w: the runs joined into the
 * pixels (join), or the pixels split into the runs */
static void move(float *px, float *const *plane, int nc, size_t w, int join)
{
    size_t x = 0;
    if (nc == 1) {
        memcpy(join ? px : plane[0], join ? plane[0] : px, w * sizeof *px);
        return;
    }
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2 && nc >= 3)
        x = join ? tex_planes_join_avx2(px, (const float *const *)plane, nc, w)
                 : tex_planes_split_avx2(plane, px, nc, w);
#endif
    for (; x < w; x++)
        for (int k = 0; k < nc; k++) {
            if (join)
                px[x * nc + k] = plane[k][x];
            else
                plane[k][x] = px[x * nc + k];
        }
}

void tex_planes_join(float *px, const float *const *plane, int nc, size_t w)
{
    move(px, (float *const *)plane, nc, w, 1);
}

void tex_planes_split(float *const *plane, const float *px, int nc, size_t w)
{
    move((float *)px, plane, nc, w, 0);
}
