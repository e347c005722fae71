/* camera.c - the eye's rays */
#include <math.h>

#include "render/camera.h"
#include "render/scene.h"
#include "render/x86/camera_x86.h"

void tex_camera_setup(const struct tex_scene *s, struct tex_camera *cam)
{
    cam->eye = s->eye;
    cam->fwd = tex_v3_norm(tex_v3_sub(s->look, s->eye));
    /* left-handed like POV-Ray: x right, y up, z into the screen */
    cam->right = tex_v3_norm(tex_v3_cross(s->up, cam->fwd));
    cam->up = tex_v3_cross(cam->fwd, cam->right);
    cam->sx = tan(s->fov * M_PI / 360);
    cam->sy = cam->sx * s->settings.h / s->settings.w;
    cam->kx = 2 * cam->sx / s->settings.w;
    cam->ky = 2 * cam->sy / s->settings.h;
    cam->spread = 2 * cam->sx / s->settings.w / sqrt(s->settings.spp);
    int k = (int)sqrt((double)s->settings.spp);
    cam->k = k * k == s->settings.spp ? k : 0;
    cam->sees_view = tex_scene_view(s, cam->eye, cam->right, cam->up, cam->fwd, &cam->view);
}

/* The bounded objects an eye ray of the pixels [x0, x1) x [y0, y1) can meet
 * (tex_view_objects; 0: none): its direction projects to the image plane at (a, b) inside
 * the pixel it samples, and the pixels' rectangle there is compared with the objects'
 * boxes'.  All of them where the tree's box is not wholly ahead. */
uint64_t tex_camera_objects(const struct tex_camera *cam, int x0, int y0, int x1, int y1)
{
    double r[4] = {x0 * cam->kx - cam->sx, x1 * cam->kx - cam->sx, cam->sy - y1 * cam->ky,
                   cam->sy - y0 * cam->ky};
    return cam->sees_view ? tex_view_objects(&cam->view, r) : ~0ull;
}

/* The eye ray of sample i of pixel (x, y), its position drawn from the pixel's rng
 * (the centre at 1 spp). */
/* Where in its pixel sample i falls: drawn from the pixel's rng (the centre at 1 spp) */
static inline void sample_offset(int spp, int k, int i, tex_rng *rng, double *ox, double *oy)
{
    *ox = *oy = 0.5;
    if (spp > 1) {
        *ox = tex_rng_uniform(rng);
        *oy = tex_rng_uniform(rng);
        if (k > 0) { /* stratified: jitter within cell i of a k x k grid */
            *ox = ((i % k) + *ox) / k;
            *oy = ((i / k) + *oy) / k;
        }
    }
}

/* sample_offset's for n <= 8 pixels of a packet, spp > 1 (ox, oy: 8 entries): the draws
 * pixel by pixel, then the cell of sample i, one for all, and the eight divisions together
 * (the same IEEE divisions, in vector registers: one at a time, each waited on the last) */
static void packet_offsets(int k, int i, tex_rng *rng, int n, double *ox, double *oy)
{
    for (int j = 0; j < n; j++) {
        ox[j] = tex_rng_uniform(&rng[j]);
        oy[j] = tex_rng_uniform(&rng[j]);
    }
    if (k > 0) {
        double cx = i % k, cy = i / k, dk = k;
        for (int j = 0; j < 8; j++)
            ox[j] = (cx + ox[j]) / dk, oy[j] = (cy + oy[j]) / dk;
    }
}

void tex_camera_ray(const struct tex_scene *s, const struct tex_camera *cam, int x, int y, int i,
                    tex_rng *rng, tex_ray *r)
{
    double ox, oy;
    sample_offset(s->settings.spp, cam->k, i, rng, &ox, &oy);
    double a = (x + ox) * cam->kx - cam->sx;
    double b = cam->sy - (y + oy) * cam->ky;
    *r = (tex_ray){cam->eye,
                   tex_v3_norm(tex_v3_add(cam->fwd, tex_v3_add(tex_v3_scale(cam->right, a),
                                                               tex_v3_scale(cam->up, b)))),
                   0, cam->spread, s->eye_media.n ? &s->eye_media : NULL, 0};
}

/* The eye rays of sample i of the packet's np pixels (x[k], y[k]) into r, made apart from
 * the traces so that their square roots overlap; eight (AVX-512) or four (AVX2) at a time in
 * lanes, their places in the pixels drawn first (each pixel's rng in its order). */
void tex_camera_rays(const struct tex_scene *s, const struct tex_camera *cam, const int *x,
                     const int *y, int np, int i, tex_rng *rng, tex_ray *r)
{
#ifdef TEX_X86
    int level = tex_simd_level(), wide = level >= TEX_SIMD_AVX512 ? 8 : 4;
    if (level >= TEX_SIMD_AVX2) {
        const struct tex_media *media = s->eye_media.n ? &s->eye_media : NULL;
        for (int k = 0; k < np; k += wide) {
            int n = np - k < wide ? np - k : wide;
            double ox[8], oy[8];
            for (int j = 0; j < 8; j++)
                ox[j] = oy[j] = 0.5;
            if (s->settings.spp > 1)
                packet_offsets(cam->k, i, rng + k, n, ox, oy);
            if (wide == 8)
                tex_eye_rays8_avx512(cam, media, x + k, y + k, ox, oy, n, r + k);
            else
                tex_eye_rays4_avx2(cam, media, x + k, y + k, ox, oy, n, r + k);
        }
        return;
    }
#endif
    for (int k = 0; k < np; k++)
        tex_camera_ray(s, cam, x[k], y[k], i, &rng[k], &r[k]);
}
