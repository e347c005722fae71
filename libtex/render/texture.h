/* texture.h - the renderer's textures: maps with mip-map pyramids, and primitives
 * evaluated at hit points (libtex internal)
 *
 * A texture is a map, looked up bilinearly in the mip-map level of the pixel's
 * footprint and linearly across two levels (mipmap.c), or a primitive (prim/prim.h)
 * evaluated where rays meet the surface: in 2D at (u, v), or as a solid texture at
 * (u, v, w).  A mapping (mapping.c) takes a hit to texture space.
 */
#ifndef TEX_TEXTURE_H
#define TEX_TEXTURE_H

#include "../base/map.h"
#include "../prim/prim.h"

#ifdef __cplusplus
extern "C" {
#endif

enum tex_mapping { TEX_MAP_NATURAL, TEX_MAP_SPHERE, TEX_MAP_CYLINDER, TEX_MAP_CONE,
                   TEX_MAP_BOX, TEX_MAP_PLANAR, TEX_MAP_SOLID, TEX_MAP_WORLD, TEX_MAP_WAVY,
                   TEX_MAP_CROSS };
/* How a cross mapping combines its two maps */
enum tex_combine { TEX_COMBINE_PRODUCT, TEX_COMBINE_MIN, TEX_COMBINE_MAX };

struct tex_texture {
    char *name;
    tex_map **mip;       /* a map's pyramid: mip[0] is the map; NULL for point primitives */
    int levels_read;     /* 1: the pyramid's levels came from a mip-mapped file, not built */
    int nlevels;
    int subregions;      /* > 0: the map holds region ids (nearest lookup, no filtering) */
    struct tex_field *field; /* a primitive evaluated at hit points */
    int solid;           /* the field is evaluated at (u,v,w) */
    const struct tex_palette *palette; /* `palette NAME`: colours the values (ops/palette.h) */
    int line, col;
};

/* Sample a texture at (u,v[,w]) with a footprint of fw texture-space units;
 * out receives RGB (grey maps repeated).  Returns the region id or 0. */
int tex_texture_eval(const struct tex_texture *t, double u, double v, double w, double fw,
                     float out[3]);
/* A mip-mapped map's (no region ids) trilinear values at n placed points (u, v in
 * [0, 1000000], repeating every unit) for footprints of squared widths fw2, as RGB into
 * out[3 n]; grad (or NULL): the gradients of their luminance per unit of u and of v into
 * grad[2 n].  In vector lanes where the CPU has AVX-512: the same bytes. */
void tex_texture_points(const struct tex_texture *t, int n, const double *u, const double *v,
                        const double *fw2, float *out, double *grad);
/* Build the pyramid of mip[0] (box filter, wrapping). */
int tex_texture_build_mip(struct tex_texture *t);

#ifdef __cplusplus
}
#endif
#endif
