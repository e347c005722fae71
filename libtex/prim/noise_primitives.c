/* noise_primitives.c - the noise primitives: gradient noise as 0.5 + 0.5 n (noise), and
 * its analytic gradient or a normal map from it (d_noise) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/prim.h"

/* ---- noise ---- */

struct noise_params {
    double frequency;
    double z;
    struct tex_reals w;
    struct tex_reals offset;
    int fade;
    int gradients;
    int frames, frame;
    double loop_radius;
};

static const struct tex_param noise_rows[] = {
    TEX_REAL(struct noise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (a whole number with --tile)"),
    TEX_NOISE_ROWS(struct noise_params),
    TEX_NOISE_W_ROW(struct noise_params),
    TEX_NOISE_LOOP_ROWS(struct noise_params),
    {0}};

struct noise_state {
    tex_noise_table t;
    tex_noise_grid g;
    int period, dims;
    double off[4];
};

/* The state shared by noise and d_noise: the lattice tables from the seed, the
 * period under --tile, and the offset in lattice units (z slice included). */
static int state_init(struct tex_field *f, double frequency, const struct tex_reals *offset,
                      double z, int gradients, int fade)
{
    struct noise_state *s = calloc(1, sizeof *s);

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    if (f->tile) {
        if (tex_noise_whole_frequency(f->prim->params, frequency) < 0)
            return -1;
        s->period = (int)frequency;
    }
    for (int a = 0; a < offset->n; a++)
        s->off[a] = offset->v[a];
    s->off[2] += frequency * z;
    if (tex_noise_init(&s->t, f->seed, gradients, s->period) < 0)
        return -1;
    s->t.fade = fade;
    return 0;
}

/* The loop's rows as every primitive with a loop has them: its messages' names */
struct loop_params {
    int frames, frame;
    double loop_radius;
};
static const struct tex_param loop_rows[] = {TEX_NOISE_LOOP_ROWS(struct loop_params), {0}};
#define LOOP_OPTION(field) TEX_OPTION(loop_rows, struct loop_params, field)

int tex_noise_loop(int frames, int frame, double radius, double *z, double *w, int *dims)
{
    if (frames == 0 && frame == 0)
        return 0;
    if (frame >= frames)
        return frames ? tex_usage_error("%s must be 0..%d for %s %d (got %d)", LOOP_OPTION(frame),
                                        frames - 1, LOOP_OPTION(frames), frames, frame)
                      : tex_usage_error("%s %d needs %s N", LOOP_OPTION(frame), frame,
                                        LOOP_OPTION(frames));
    double a = 2 * M_PI * ((double)frame / frames);
    *z += radius * cos(a);
    *w += radius * sin(a);
    *dims = 4;
    return 0;
}

static int noise_init(struct tex_field *f)
{
    const struct noise_params *p = f->params;
    struct noise_state *s;
    double z = p->z, w = p->w.n ? p->w.v[0] : 0;
    int dims = p->w.n ? 4 : 3;

    if (tex_noise_loop(p->frames, p->frame, p->loop_radius, &z, &w, &dims) < 0 ||
        state_init(f, p->frequency, &p->offset, z, p->gradients, p->fade) < 0)
        return -1;
    s = f->state;
    s->dims = dims;
    s->off[3] = dims == 4 ? p->frequency * w : 0;
    if (f->w > 0 && f->h > 0)
        return tex_noise_grid_init(&s->g, &s->t, f->w, f->h, p->frequency, p->frequency, s->off,
                                   s->dims, s->period);
    return 0;
}

static void noise_fini(struct tex_field *f)
{
    struct noise_state *s = f->state;
    if (!s)
        return;
    tex_noise_free(&s->t);
    tex_noise_grid_free(&s->g);
    free(s);
}

static inline float to_unit(float s)
{
    return clamp01(0.5f + 0.5f * s);
}

static void noise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                        const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct noise_params *p = f->params;
    const struct noise_state *s = f->state;
    double fr = p->frequency, X[B], Y[B], Z[B], W[B], r[B];
    float rf[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        if (s->dims == 3) { /* the coordinates below, made in the kernel */
            tex_noise_points_at(&s->t, s->period, s->off, fr, m, u + i0, v + i0,
                                w ? w + i0 : NULL, rf);
#pragma omp simd
            for (int i = 0; i < m; i++)
                out[i0 + i] = to_unit(rf[i]);
            continue;
        }
#pragma omp simd
        for (int i = 0; i < m; i++) { /* lattice coordinates: offset + frequency x point */
            X[i] = s->off[0] + fr * u[i0 + i];
            Y[i] = s->off[1] + fr * v[i0 + i];
            Z[i] = s->off[2] + fr * (w ? w[i0 + i] : 0);
            W[i] = s->off[3];
        }
        tex_noise_points(&s->t, s->period, s->dims, m, X, Y, Z, W, r);
        for (int i = 0; i < m; i++)
            out[i0 + i] = to_unit((float)r[i]);
    }
}

static void noise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    noise_eval3(f, n, u, v, NULL, out);
}

static void noise_row(const struct tex_field *f, int y, float *out)
{
    const struct noise_state *s = f->state;

    tex_noise_grid_row_op(&s->g, y, TEX_ROW_UNIT, 0, 0, 0, out);
}

const struct tex_primitive tex_prim_noise = {
    .name = "noise",
    .summary = "gradient noise of the thesis (Perlin) as 0.5 + 0.5 n: mostly 0.2..0.8 in a map, "
               "never past 0..1 (t_remap --levels stretches it)",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct noise_params),
    .params = noise_rows,
    .init = noise_init,
    .fini = noise_fini,
    .eval2 = noise_eval2,
    .eval3 = noise_eval3,
    .row = noise_row,
};

/* ---- d_noise: the analytic gradient (thesis 5.2.2.3) ---- */

struct dnoise_params {
    double frequency, z, strength;
    struct tex_reals offset;
    int channels, normal, fade, gradients;
};

static const struct tex_param dnoise_rows[] = {
    TEX_REAL(struct dnoise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (a whole number with --tile)"),
    TEX_NOISE_ROWS(struct dnoise_params),
    TEX_INT(struct dnoise_params, channels, 0, 2, 2, 3, "N",
            "2: d/dx, d/dy; 3: also d/dz (raw gradient, lattice units)", .old = "-c"),
    TEX_FLAG(struct dnoise_params, normal, 0,
             "write a tangent-space normal map (x right, y up, z out) encoded as 0.5 + 0.5 n"),
    TEX_REAL(struct dnoise_params, strength, 0, 1, 0, 1e6, "S",
             "--normal: height scale, n = normalize(-S dn/dx, S dn/dy_up, 1)"),
    {0}};

#define DNOISE_OPTION(field) TEX_OPTION(dnoise_rows, struct dnoise_params, field)

static int dnoise_init(struct tex_field *f)
{
    const struct dnoise_params *p = f->params;
    struct noise_state *s;

    /* Values other than the defaults are the test: the rows are shared with scenes. */
    if (!p->normal && p->strength != 1)
        return tex_usage_error("%s applies with %s only", DNOISE_OPTION(strength),
                               DNOISE_OPTION(normal));
    if (p->normal && p->channels != 2)
        return tex_usage_error("%s applies without %s only (a normal map has 3)",
                               DNOISE_OPTION(channels), DNOISE_OPTION(normal));
    f->nc = p->normal ? 3 : p->channels;
    if (state_init(f, p->frequency, &p->offset, p->z, p->gradients, p->fade) < 0)
        return -1;
    s = f->state;
    s->dims = 3;
    if (f->w > 0 && f->h > 0)
        return tex_noise_grid_init(&s->g, &s->t, f->w, f->h, p->frequency, p->frequency, s->off,
                                   3, s->period);
    return 0;
}

static void dnoise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                         const double *w, float *out)
{
    const struct dnoise_params *p = f->params;
    const struct noise_state *s = f->state;
    double fr = p->frequency;

    for (int i = 0; i < n; i++, out += f->nc) {
        double g[3];
        tex_noise3_grad(&s->t, s->period, s->off[0] + fr * u[i], s->off[1] + fr * v[i],
                        s->off[2] + fr * (w ? w[i] : 0), g);
        if (p->normal) {
            /* v grows downwards: the height's slope along y-up is -dn/dv. */
            double nx = -p->strength * g[0], ny = p->strength * g[1];
            double len = sqrt(nx * nx + ny * ny + 1);
            out[0] = (float)(0.5 + 0.5 * nx / len);
            out[1] = (float)(0.5 + 0.5 * ny / len);
            out[2] = (float)(0.5 + 0.5 / len);
        } else {
            for (int c = 0; c < f->nc; c++)
                out[c] = (float)g[c];
        }
    }
}

static void dnoise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                         float *out)
{
    dnoise_eval3(f, n, u, v, NULL, out);
}

/* Grid rows: the gradient from the vectorised rows (float, within about 1e-5
 * of the points' double), then interleaved or made a normal. */
static void dnoise_row(const struct tex_field *f, int y, float *out)
{
    const struct dnoise_params *p = f->params;
    const struct noise_state *s = f->state;
    float *d = malloc(3 * (size_t)f->w * sizeof *d), S = (float)p->strength;

    if (!d) { /* no memory for the row buffers: the point path needs none */
        for (int x = 0; x < f->w; x++) {
            double u = (x + 0.5) / f->w, v = (y + 0.5) / f->h;
            dnoise_eval2(f, 1, &u, &v, out + (size_t)x * f->nc);
        }
        return;
    }
    tex_noise_grid_row_grad(&s->g, y, d, d + f->w, f->nc == 3 && !p->normal ? d + 2 * f->w : NULL);
    for (int x = 0; x < f->w; x++, out += f->nc) {
        float gx = d[x], gy = d[f->w + x];
        if (p->normal) {
            /* v grows downwards: the height's slope along y-up is -dn/dv. */
            float nx = -S * gx, ny = S * gy, len = sqrtf(nx * nx + ny * ny + 1);
            out[0] = 0.5f + 0.5f * (nx / len);
            out[1] = 0.5f + 0.5f * (ny / len);
            out[2] = 0.5f + 0.5f / len;
        } else {
            out[0] = gx;
            out[1] = gy;
            if (f->nc == 3)
                out[2] = d[2 * f->w + x];
        }
    }
    free(d);
}

const struct tex_primitive tex_prim_d_noise = {
    .name = "d_noise",
    .summary = "the analytic gradient of gradient noise, or a normal map from it",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct dnoise_params),
    .params = dnoise_rows,
    .init = dnoise_init,
    .fini = noise_fini,
    .eval2 = dnoise_eval2,
    .eval3 = dnoise_eval3,
    .row = dnoise_row,
};
