/* camera.h - the eye: a pinhole camera and its rays (libtex internal)
 *
 * Left-handed like POV-Ray: x right, y up, z into the screen; the field of view is
 * horizontal.  A pixel's samples are the centre at 1 spp, else drawn from its rng,
 * stratified on a k x k grid where spp = k^2.  Each ray carries the spread of its
 * footprint (the pixel's angle), which the filtered lookups take.
 */
#ifndef TEX_CAMERA_H
#define TEX_CAMERA_H

#include <stdint.h>

#include "bvh.h"
#include "../base/rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The eye and its image plane, made once per render */
struct tex_camera {
    tex_v3 eye, fwd, right, up;
    double sx, sy; /* half extents of the image plane at distance 1 */
    double kx, ky; /* 2 sx / w and 2 sy / h: image plane units per pixel */
    double spread; /* footprint growth per unit distance of a sample's ray */
    int k;         /* spp = k * k: stratified, else 0 */
    struct tex_view view; /* the bounded objects' box on the image plane (right, up) */
    int sees_view;        /* 0: the box is not wholly ahead, and every packet traces it */
};

/* The camera of scene s, for its image size and samples per pixel */
void tex_camera_setup(const struct tex_scene *s, struct tex_camera *cam);
/* The bounded objects an eye ray of the pixels [x0, x1) x [y0, y1) can meet
 * (tex_view_objects; 0: none): its direction projects to the image plane at (a, b) inside
 * the pixel it samples, and the pixels' rectangle there is compared with the objects'
 * boxes'.  All of them where the tree's box is not wholly ahead. */
uint64_t tex_camera_objects(const struct tex_camera *cam, int x0, int y0, int x1, int y1);
/* The eye ray of sample i of pixel (x, y), its position drawn from the pixel's rng
 * (the centre at 1 spp). */
void tex_camera_ray(const struct tex_scene *s, const struct tex_camera *cam, int x, int y, int i,
                    tex_rng *rng, tex_ray *r);
/* The eye rays of sample i of the packet's np pixels (x[k], y[k]) into r, made apart from
 * the traces so that their square roots overlap; at 1 spp eight at a time in lanes. */
void tex_camera_rays(const struct tex_scene *s, const struct tex_camera *cam, const int *x,
                     const int *y, int np, int i, tex_rng *rng, tex_ray *r);

#ifdef __cplusplus
}
#endif
#endif
