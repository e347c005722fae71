/* surface.h - surfaces and the textures they apply through application functions
 * (libtex internal)
 *
 * A surface applies textures in order; each one maps the hit point to texture space (its
 * mapping), keeps the point only inside its window (u1,v1)-(u2,v2), repeats the map
 * nu x nv times there (1 x 1 stretches it), looks up the value f and changes the shading
 * parameters through its application functions g[region][param] (thesis 4.3.4, 5.3).
 * The material at a hit comes from tex_resolve_material (appfn.c); a packet's hits look
 * their textures up ahead, together (packet.c).
 */
#ifndef TEX_SURFACE_H
#define TEX_SURFACE_H

#include "colour.h"
#include "render_shade.h"
#include "render.h"
#include "shape.h"
#include "texture.h"
#include "../lang/expr.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_scene;
/* A hit's textures looked up ahead, with the other hits of its packet (render.c traces
 * a tile's eye rays first): for the first TEX_PREFETCH_MAX textures its surface sf
 * applies, where the mapping took the hit (as tex_resolve_material would find it) and,
 * for primitives evaluated at hit points, their values from one call over the packet. */
#define TEX_PREFETCH_MAX 8
struct tex_prefetch {
    const struct tex_surface *sf; /* the surface these are for; NULL: none */
    const struct tex_object *leaf;
    tex_v3 P, pl;                 /* the hit, in world and in its leaf's object space */
    tex_v3 D, N;                  /* the shading frame's ray and normal (width > 0) */
    double width;                 /* the footprint's width there, 0 if not filtered */
    int n;                        /* applied textures prefetched */
    struct tex_prefetch_ap {
        const struct tex_texture *tex;
        double uvw0[3], uvw[3]; /* the mapping's coordinates, then placed (if inside) */
        int face, inside, pending, has_val; /* pending: a value still to evaluate */
        int bump; /* a function of its texture bumps (struct placement's) */
        double fw; /* a map's footprint (squared), looked up with it */
        double grad[2]; /* a bumped map's gradient (map_eval's) */
        int has_tilt;   /* and the tilt's direction, made ahead (the bump scales it) */
        double tilt[3];
        float val[TEX_MAP_MAX_CHANNELS]; /* the primitive's value; a map's as RGB (has_val) */
    } ap[TEX_PREFETCH_MAX];
};
/* Where a ray met a surface, as the application functions see it. */
struct tex_shade_at {
    const struct tex_object *leaf;
    const tex_v3 *P, *D; /* the world point, the ray's unit direction */
    double width;        /* the ray's footprint at P (filtered lookups if the scene filters) */
    double dist;         /* the path's length from the eye to P */
    int depth;           /* 0 for eye rays, +1 per reflection or refraction */
    const struct tex_prefetch *pre; /* the hit's prefetched lookups, or NULL */
};
/* A packet's lookups ahead (render.c): pf's mapping of the hit P on leaf, surface sf;
 * then the values of every primitive at the pending points of the n hits pf[i], each
 * primitive in batched calls (eval3 / eval2 over many points), and of a surface's first
 * texture where it is a mip-mapped map, footprints and all (and where bumped, its
 * gradient and the tilt's direction). */
void tex_prefetch_map(struct tex_prefetch *pf, const struct tex_surface *sf,
                      const struct tex_object *leaf, const tex_v3 *P);
/* Whether sf's lookups ahead take footprints (a band-limited solid texture, a mip-mapped
 * map); then, after tex_prefetch_map, the hit's shading frame as tex_resolve_material gets
 * it (D, N as shade() orients it; width 0 when the scene does not filter). */
int tex_surface_footprints(const struct tex_surface *sf);
void tex_prefetch_footprints(struct tex_prefetch *pf, const tex_v3 *D, const tex_v3 *N,
                             double width);
void tex_prefetch_eval(struct tex_prefetch *const *pf, int n);
/* A packet's hits on one leaf whose surface's one map is mapped planar on a plane (a
 * plane's natural mapping is) or natural on a box, cylinder, cone or sphere are looked up
 * in vector lanes from end to end: mapping (gradients and all), footprint and trilinear
 * lookup, with no pass through the records between the steps (tex_prefetch_lanes).  Their
 * records, and their points, shading frames (D, N as shade() orients them) and footprint
 * widths in rows. */
#define TEX_LANES 64
struct tex_lanes {
    int n;
    const struct tex_surface *sf;
    const struct tex_object *leaf;
    struct tex_prefetch *pf[TEX_LANES];
    double p[3][TEX_LANES], d[3][TEX_LANES], nn[3][TEX_LANES], w[TEX_LANES];
};
/* Whether the hit of record pf on leaf (surface sf, whose lookups take footprints; P, D, N
 * and width > 0 as for tex_prefetch_footprints) goes in L's lanes: 1, queued there (a
 * direct surface, tex_resolve_material's short way, whose map's mapping the lanes make:
 * a plane's where the CPU has AVX2, the natural ones too with AVX-512; and the same leaf
 * as the hits queued before); else 0, for
 * tex_prefetch_map and the rest. */
int tex_lanes_take(struct tex_lanes *L, struct tex_prefetch *pf, const struct tex_surface *sf,
                   const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *D,
                   const tex_v3 *N, double width);
/* The queued hits' records made as tex_prefetch_map, tex_prefetch_footprints and
 * tex_prefetch_eval make them, the same bytes; those the lanes cannot finish (outside the
 * map's window, seen head-on) are mapped the usual way and listed in rest for
 * tex_prefetch_eval: returns how many.  L is emptied. */
int tex_prefetch_lanes(struct tex_lanes *L, struct tex_prefetch **rest);
/* The material at a hit (surface sf): the application functions evaluated,
 * N bent by bump and normal maps, colours in the scene's colour space;
 * m[1] is the blended surface's where m[0].blend > 0 (its weight).
 * sf's cache must be filled (tex_surface_cache). */
void tex_resolve_material(const struct tex_scene *s, const struct tex_surface *sf,
                          const struct tex_shade_at *at, tex_v3 *N, struct tex_material m[2]);
/* Whether sf's material at a hit is a plain one, Whitted-Phong without a blend or rays of
 * its own (Kr and Kt 0, neither textured): 0, not; 1, untextured or a direct surface (see
 * tex_lanes_take) whose functions are compiled ones of Kd alone, whose material
 * tex_plain_material gives from the hit's lookups ahead pre (0 where they were not made);
 * 2, any other, whose material (and normal N, bent) tex_plain_resolve gives through
 * tex_resolve_material's path, at.  In an RGB scene: the colours and exponent
 * tex_resolve_material would give (Kr and Kt stay 0). */
struct tex_plain {
    float ka[3], kd[3], ks[3];
    double n;
};
int tex_surface_plain(const struct tex_surface *sf);
int tex_plain_material(const struct tex_surface *sf, const struct tex_prefetch *pre,
                       struct tex_plain *m);
/* later (or NULL): where sf's Kd function is an expression run better with other hits'
 * (tex_surface_cache's choice), it is left there to run (tex_plain_later_run) and m's Ka
 * and Kd wait for it; later->fn stays NULL where nothing was left */
struct tex_plain_later;
void tex_plain_resolve(const struct tex_scene *s, const struct tex_surface *sf,
                       const struct tex_shade_at *at, tex_v3 *N, struct tex_plain *m,
                       struct tex_plain_later *later);
/* Fill (tex_scene_prepare) and free (tex_scene_free) a surface's cache: its untextured
 * colours in the scene's colour space, its application functions compiled. */
int tex_surface_cache(struct tex_surface *sf, const struct tex_colour_space *cs);
void tex_surface_uncache(struct tex_surface *sf);

/* The parameters an application function can set: the surface's Ka..ior, then bump,
 * Cook-Torrance's m and s, the weight of a blended surface, a tangent-space normal map,
 * a height gradient, the point, and the anisotropic models' roughnesses, tangent angle and
 * flow field (tex_sparam_row gives each one's row). */
enum tex_sparam { TEX_SP_KA, TEX_SP_KD, TEX_SP_KS, TEX_SP_N, TEX_SP_KR, TEX_SP_KT, TEX_SP_IOR,
                  TEX_SP_BUMP, TEX_SP_M, TEX_SP_S, TEX_SP_BLEND, TEX_SP_NORMAL,
                  TEX_SP_GRADIENT, TEX_SP_P, TEX_SP_AU, TEX_SP_AV, TEX_SP_ANGLE,
                  TEX_SP_TANGENT, TEX_SP_COUNT };

/* An application function's expression, compiled (lang/expr.h): a postfix
 * program over f (the map value), p (the untextured value), numbers, colours,
 * other textures (a cascade) and the renderer's quantities at the hit, run
 * per RGB channel.  Its operands: */
enum tex_eleaf { TEX_LEAF_F, TEX_LEAF_P, TEX_LEAF_TEX /* ptr: the texture */,
                 TEX_LEAF_Q /* TEX_LEAF_Q + q: quantity q */ };

/* The renderer's quantities an application function can read (composition
 * at application time, thesis 5.2.4.1): their names and help are
 * tex_quantities[q], in this order. */
enum tex_quantity { TEX_Q_DIST, TEX_Q_FOOTPRINT, TEX_Q_LOD, TEX_Q_NDOTV, TEX_Q_DEPTH,
                    TEX_Q_X, TEX_Q_Y, TEX_Q_Z, TEX_Q_OX, TEX_Q_OY, TEX_Q_OZ,
                    TEX_Q_U, TEX_Q_V, TEX_Q_W, TEX_Q_NX, TEX_Q_NY, TEX_Q_NZ, TEX_Q_REGION,
                    TEX_Q_FACE, TEX_Q_COUNT };
extern const struct tex_scene_word tex_quantities[TEX_Q_COUNT + 1]; /* render.h */

/* g[region][parameter] = h: one application function. */
struct tex_appfn {
    int region;          /* 0: every region (or a map without regions) */
    enum tex_sparam param;
    double lo, hi;       /* the range results are clamped to: tex_sparam_row(param)'s */
    struct tex_expr *e;
    struct tex_appfn *next;
};

/* A plain hit's Kd function left by tex_plain_resolve: its expression's operands as the hit
 * has them, and the Ka that scales the result (material's Ka Kd) */
#define TEX_LATER_MAX 64 /* hits run together */
struct tex_plain_later {
    const struct tex_appfn *fn; /* NULL: none left */
    float f[3], p[3], ka;
    double uvw[3], fw2;
    int has_q;
    double q[TEX_Q_COUNT];
};
/* The n hits' functions left in later[i] run, the expressions' programs walked once for the
 * hits that share one (their palettes looked up together), and Ka and Kd of m[i] made: the
 * floats tex_plain_resolve gives without later */
void tex_plain_later_run(struct tex_plain_later *later, struct tex_plain *m, int n);

/* One texture applied to a surface: its mapping, window, placement and functions. */
struct tex_apply {
    const struct tex_texture *tex;
    enum tex_mapping mapping;
    double u1, v1, u2, v2; /* the texture window */
    double nu, nv;         /* repeat counts (1 1: stretch) */
    double scale;          /* world / planar mapping: texture units per world unit */
    double size[2];        /* natural: one map per W x H object units (thesis 5.3.1's
                            * non-elastic mapping); 0 0: across the shape (elastic) */
    /* projections (thesis 5.2.1.3): the texture's frame relative to the object, its y axis
     * along `axis`, then rotated and translated; to_tex takes points into it */
    tex_v3 axis;
    tex_xform place, to_tex;
    int placed;                        /* 1: to_tex is not the identity */
    double wave[2];                    /* wavy: amplitude (in u) and wavelength (along y) */
    const struct tex_texture *cross;   /* cross: the map on the y-z plane */
    enum tex_combine combine;          /* cross: how the two maps combine */
    struct tex_appfn *fns;
    struct tex_apply *next;
    int line, col;
};

/* The optical characters a surface may be described by (thesis 4.4, items 6 and 7), each a
 * consistent set of the shading parameters that model it (table 4.1): the largest of Kd's
 * channels plus Ks, Kr and Kt is at most 1.  words[i] is a row of tex_surface_rows and its
 * value, as a scene writes them; NULL ends. */
#define TEX_CHARACTERS "matte|glossy|metal|glass|varnished"

/* Where an anisotropic surface's tangent comes from (its `tangent` row, anisotropic.h) */
enum tex_tangent_from { TEX_TANGENT_U, TEX_TANGENT_V, TEX_TANGENT_FIXED };
struct tex_character {
    const char *name;
    const char *words[8][2];
};
extern const struct tex_character tex_characters[];

struct tex_surface {
    char *name;
    float ka, kd[3], ks[3]; /* ka scalar times kd colour; ks scalar times white or colour */
    double n, kr, kt, ior;
    const struct tex_shading_model *model;
    struct tex_ct *ct;      /* Cook-Torrance parameters (render_ct.h); NULL: its defaults */
    double alpha[2];        /* ward, ashikhmin-shirley: roughness along and across T */
    enum tex_tangent_from tangent_from; /* their tangent (anisotropic.h) */
    tex_v3 tangent;                     /* TEX_TANGENT_FIXED's, world */
    const struct tex_surface *blend; /* `blend SURFACE`: mixed in by `blend = h`, or NULL */
    int character;                   /* `character NAME`: 1 + its index in tex_characters, or 0 */
    struct tex_apply *apply;
    int line, col;
    struct tex_surface_cache *cache; /* tex_scene_prepare's (appfn.c), or NULL */
};

#ifdef __cplusplus
}
#endif
#endif
