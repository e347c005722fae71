/* render.h - t_apply's ray tracer: load a scene, set options, render, free
 *
 * A Whitted ray tracer that maps texture maps onto CSG objects through the
 * thesis's application functions.  The scene language is t_apply(5).
 *
 *   struct tex_scene *s = tex_scene_load("vase.scene");   // NULL + tex_errmsg()
 *   // or tex_scene_parse(text, len, "name") for text in memory
 *   if (tex_scene_set_size(s, 800, 600) < 0 ||          // overrides, optional
 *       tex_scene_prepare(s) < 0)                        // then prepare, once
 *       ...;
 *   fputs(tex_scene_warnings(s), stderr);                // "" when none
 *   tex_map *img = tex_render(s, progress_fn, NULL);     // linear RGB, 3 channels
 *   tex_scene_free(s);
 *
 * Errors name the place: "vase.scene:12:7: unknown texture 'wood'".  The
 * scene's internals are libtex's own (render/scene.h, not installed).
 */
#ifndef TEX_RENDER_H
#define TEX_RENDER_H

#include <stddef.h>

#include "../base/api.h"
#include "../base/map.h"
#include "../base/param.h"

TEX_API_BEGIN

struct tex_scene;
struct tex_shading_model;

#define TEX_SCENE_MAX_SIDE 16384 /* image W H and t_apply -s */

struct tex_scene *tex_scene_load(const char *path); /* "-" is not allowed: maps use stdin */
struct tex_scene *tex_scene_parse(const char *text, size_t len, const char *name);
/* Limits for scenes from untrusted places (the fuzz target): a texture with no
 * size that must be sampled into a map is sampled at sample_size (default 512). */
struct tex_scene_opts {
    int sample_size; /* 1..TEX_SCENE_MAX_SIDE */
};
#define TEX_SCENE_DEFAULTS {512}
struct tex_scene *tex_scene_parse_opts(const char *text, size_t len, const char *name,
                                       const struct tex_scene_opts *o);
void tex_scene_free(struct tex_scene *s);
/* The materials database a scene reads by default, into path: $TEXTURA_MATERIALS,
 * materials.txt beside the scene (scene may be NULL), or the installed
 * patterns/materials.txt. */
const char *tex_scene_materials_path(const char *scene, char *path, size_t n);

/* Overrides of the scene's settings, before tex_scene_prepare; -1 with a
 * usage error out of range. */
int tex_scene_set_size(struct tex_scene *s, int w, int h); /* 1..TEX_SCENE_MAX_SIDE */
void tex_scene_size(const struct tex_scene *s, int *w, int *h); /* the image's, as set */
int tex_scene_set_samples(struct tex_scene *s, int spp);   /* per pixel, 1..4096 */
void tex_scene_set_threads(struct tex_scene *s, int n);    /* 0: one per core */
/* The colour model: 0 for RGB, else spectral with that many bands (1..64);
 * frees the previous one. */
int tex_scene_set_colour(struct tex_scene *s, int bands);
/* A shading model by name (phong, cook-torrance), or NULL; and every
 * surface shaded by it. */
const struct tex_shading_model *tex_shading_find(const char *name);
void tex_scene_set_model(struct tex_scene *s, const struct tex_shading_model *m);

/* Build the BVH, check the settings (after the overrides) and find the media
 * around the camera: the transparent solids containing the eye, outermost
 * first, each with the index of the surface a ray leaves it by. */
int tex_scene_prepare(struct tex_scene *s);
/* What the scene's checks found worth saying, one line each ("" if nothing). */
const char *tex_scene_warnings(const struct tex_scene *s);
/* Thesis 4.4, item 8: a warning (tex_scene_warnings) for each surface whose Kd + max(Ks, Kr)
 * + Kt can pass 1, its own or where its textures set them (appfn.h's tex_surface_energy);
 * the number of such surfaces. */
int tex_scene_check_energy(struct tex_scene *s);

/* Render: linear RGB, 3 channels.  progress(done, total, arg) is called
 * from the master thread now and then (may be NULL). */
tex_map *tex_render(struct tex_scene *s, void (*progress)(long done, long total, void *arg),
                    void *arg);
/* Only the rw x rh region at (rx, ry) of the image, bit-identical to the same
 * pixels of tex_render (each pixel is seeded by its place in the whole image);
 * the map records its place (map.h).  A region outside the image is a usage error. */
tex_map *tex_render_region(struct tex_scene *s, int rx, int ry, int rw, int rh,
                           void (*progress)(long done, long total, void *arg), void *arg);
/* The same region's pixels into px (rw x rh RGB floats, row by row), the caller's: a
 * band of a render written as it is made (t_apply).  0, or -1 with the error set. */
int tex_render_rows(struct tex_scene *s, int rx, int ry, int rw, int rh, float *px);

/* The scene's blocks by name ("settings", "camera", "light", "environment", "texture",
 * "surface", "apply", "object") with their parameter rows, for help and the man page;
 * the list ends with a NULL name. */
struct tex_scene_block {
    const char *name;
    const struct tex_param *rows;
};
extern const struct tex_scene_block tex_scene_blocks[];

/* The words of application functions' expressions, for help and the man
 * page: the quantities of the hit (args NULL; the list ends with a NULL
 * name), and function i (args: its arguments' names; 0 past the last). */
struct tex_scene_word {
    const char *name, *args, *help;
};
extern const struct tex_scene_word tex_quantities[];
int tex_scene_function(int i, struct tex_scene_word *w);

TEX_API_END
#endif
