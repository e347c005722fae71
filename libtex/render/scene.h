/* scene.h - t_apply's scene inside the ray tracer (libtex internal; the public
 * interface is render.h: load, set options, render, free)
 *
 * A minimal Whitted ray tracer (thesis 4.3.4-4.4, 5.3; DESIGN section 6) that maps
 * texture maps onto CSG objects through application functions.  The scene language is
 * described in t_apply(5).
 *
 * Errors name the place: "vase.scene:12:7: unknown texture 'wood'".  Warnings (e.g. the
 * camera inside an object) are kept in s->warnings, one per line, for the tool to print.
 *
 * Headers and files by concept (Rayshade's and pbrt's split):
 *   vecmath.h        vectors, transforms, rays, media (render_media.c: the stack of
 *                    nested transparent media along a ray)
 *   shape.h          sphere, box, cylinder, cone, plane, torus and CSG (render_shape.c)
 *   bvh.h            the bounding-volume hierarchy, CSG balancing, the scene's ray
 *                    queries (render_bvh.c)
 *   texture.h        textures: maps with mip-maps (mipmap.c), primitives at hit points
 *   mapping.h        mappings into texture space, windows and placement (mapping.c)
 *   footprint.h      the pixel's footprint on a surface in texture units (footprint.c)
 *   surface.h        surfaces and application functions (appfn.c); a packet's lookups
 *                    ahead (packet.c; x86/ for the AVX-512 lanes)
 *   light.h          distant, point, spot and area lights (render_light.c)
 *   render_shade.h   shading models (Whitted-Phong, render_shade.c); render_ct.h,
 *                    Cook-Torrance (render_ct.c)
 *   scene.h          the scene and its rows (render_params.c), the scene language
 *                    (render_scene.c, through lang/lex.h and lang/expr.h)
 *   render.c         camera, sampling, the integrator (direct light, reflection,
 *                    refraction), tiles and threads
 */
#ifndef TEX_SCENE_H
#define TEX_SCENE_H

#include <stdint.h>

#include "bvh.h"
#include "colour.h"
#include "light.h"
#include "surface.h"
#include "../base/param.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the scene ------------------------------------------------------------ */

struct tex_settings {
    int w, h, spp, depth, threads;
    int filter;       /* 1: mip-mapped texture lookups */
    uint64_t seed;
    double bailout;   /* reflected/refracted rays weighing less are not traced */
};

struct tex_bvh;

/* `environment FILE { ... }`: a lat-long map (Blinn and Newell's reflection map, thesis
 * 2.2.2) that rays leaving the scene look up by their direction: u = 0.5 + atan2(x, z) / 2pi
 * (+z, the default view, at the map's centre), v = acos(y) / pi (up at the top row). */
struct tex_environment {
    struct tex_texture *map;  /* NULL: the background colour */
    tex_v3 rotate;            /* degrees about x, y, z, as objects turn */
    double intensity;
    tex_xform to_map;         /* world directions into the map's frame */
};

struct tex_procs;
struct tex_scene {
    char *file;
    struct tex_procs *procs; /* composed primitives (lang/proc.h), or NULL */
    tex_v3 eye, look, up;
    double fov;                 /* horizontal, degrees */
    struct tex_settings settings;
    float ambient[3], background[3];
    struct tex_environment env;
    struct tex_colour_space cs;
    struct tex_light *lights;
    int nlights;
    struct tex_object **objects; /* top-level objects */
    int nobjects, cobjects;      /* in use, allocated */
    struct tex_hyper **hypers;   /* hypertextures (hypertexture.h), marched by volume.c */
    int nhypers;
    struct tex_bvh *bvh;
    struct tex_media eye_media; /* the transparent solids the camera is inside (prepare's) */
    /* everything allocated, freed together */
    struct tex_texture **textures;
    int ntextures;
    struct tex_surface **surfaces;
    int nsurfaces;
    struct tex_palette **palettes; /* the palettes scenes name (ops/palette.h) */
    int npalettes;
    void **pool;
    size_t npool, cpool;
    char *warnings;
    void *packets; /* render.c's packets, one a thread, kept from band to band */
    size_t packets_mapped;
    int npackets;
};

/* A warning for the tool to print, "file:line:col: warning: ...", added to s->warnings */
void tex_scene_warn(struct tex_scene *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* ---- the scene's parameters as rows (render_params.c) ------------------------ */

/* One table per block of t_apply(5), rows as in param.h: each row gives a
 * word, its type, default, range and help, and where the value is stored.
 * The scene parser reads a block by looking its words up here; t_apply
 * --help-scene prints them and t_apply(5)'s lists are made from them. */
extern const struct tex_param tex_settings_rows[]; /* top level, over struct tex_scene */
extern const struct tex_param tex_camera_rows[];   /* camera { }, over struct tex_scene */
extern const struct tex_param tex_light_rows[];    /* light KIND { }, over struct tex_light;
                                                    * kinds: bit enum tex_light_kind */
extern const struct tex_param tex_surface_rows[];  /* surface NAME { }, over struct tex_surface;
                                                    * rows 0..TEX_SP_IOR are Ka..ior in
                                                    * enum tex_sparam order */
extern const struct tex_param tex_apply_rows[];    /* apply TEXTURE { }, over struct tex_apply */
extern const struct tex_param tex_object_rows[];   /* SHAPE { }, over struct tex_shape_params;
                                                    * kinds: bit enum tex_shape_kind; surface
                                                    * and the transforms are also CSG words */
extern const struct tex_param tex_target_rows[];   /* bump, m, s, blend, normal, gradient:
                                                    * TEX_SP_BUMP.. in order */
extern const struct tex_param tex_environment_rows[]; /* environment FILE { }, over
                                                       * struct tex_environment */
extern const struct tex_param tex_hyper_rows[];    /* hypertexture { }, over struct tex_hyper */
extern const struct tex_param tex_hyper_fn_rows[]; /* its functions: enum tex_hyper_fn order */
extern const struct tex_param tex_hdensity_rows[]; /* its densities' words, over struct
                                                    * tex_hdensity; kinds: bit enum
                                                    * tex_hdensity_kind */
/* The readers of the rows that the scene language's own code reads (TEX_P_SPECIAL;
 * render_scene.c): reader is its parser, ctx the block being read. */
tex_param_read tex_scene_read_seed, tex_scene_read_colour, tex_scene_read_materials;
tex_param_read tex_scene_read_spectrum, tex_scene_read_falloff;
tex_param_read tex_scene_read_model, tex_scene_read_character, tex_scene_read_material,
    tex_scene_read_facets,
    tex_scene_read_specular, tex_scene_read_apply, tex_scene_read_blend, tex_scene_read_tangent;
tex_param_read tex_scene_read_translate, tex_scene_read_rotate, tex_scene_read_scale,
    tex_scene_read_cross, tex_scene_read_stretch, tex_scene_read_region;
tex_param_read tex_scene_read_surface;
/* The environment's colour (RGB, times its intensity) in direction d (unit, world), for a
 * ray whose footprint spreads by `spread` radians (0: no filtering). */
void tex_environment_eval(const struct tex_environment *e, const tex_v3 *d, double spread,
                          float rgb[3]);
/* The row of an application function's parameter: its name and the range its
 * results are clamped to. */
const struct tex_param *tex_sparam_row(enum tex_sparam sp);

#ifdef __cplusplus
}
#endif
#endif
