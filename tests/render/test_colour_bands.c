/* test_colour_bands.c - the band loops bit for bit: colour.h's per-sample operations and
 * tex_colour_max, spectrum.h's XYZ sums, RGB-to-bands and gamut map, at 16 bands (their
 * loops of constant length) and at other counts, against plain scalar loops in main's order */
#include "base/error.h"
#include "render/colour.h"
#include "render/spectrum.h"
#include "unit.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static uint64_t state = 88172645463325252ull;

/* a float of any magnitude and sign, with zeros, -0, tiny and huge ones among them */
static float draw(void)
{
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    uint32_t r = (uint32_t)(state >> 32);
    switch (r % 8) {
    case 0: return 0;
    case 1: return -0.0f;
    case 2: return ldexpf((float)(r >> 8) / (1 << 24), (int)(r % 61) - 40); /* wide range */
    default: return (float)(r >> 8) / (1 << 24) * ((r & 16) ? -1.5f : 1.5f);
    }
}

static void fill(tex_colour *c)
{
    for (int i = 0; i < TEX_COLOUR_MAX; i++)
        c->v[i] = draw();
}

static int same(const void *a, const void *b, size_t n)
{
    return !memcmp(a, b, n);
}

/* tex_colour_max as a scalar loop: v[0], then each larger sample (a NaN never is) */
static float max_ref(const tex_colour *a, int n)
{
    float m = a->v[0];
    for (int i = 1; i < n; i++)
        m = a->v[i] > m ? a->v[i] : m;
    return m;
}

static void colour_ops(void)
{
    const int ns[] = {3, 7, 8, 12, 16, 20, 64};
    int bad[5] = {0};
    for (int k = 0; k < 7; k++) {
        int n = ns[k];
        for (int t = 0; t < 300; t++) {
            tex_colour a, b, d, r, out;
            fill(&a), fill(&b), fill(&d);
            float s = draw();
            r = d; /* d += a b s */
            for (int i = 0; i < n; i++)
                r.v[i] = d.v[i] + a.v[i] * b.v[i] * s;
            out = d;
            tex_colour_mmadd(&out, n, &a, &b, s);
            bad[0] += !same(&out, &r, sizeof out);
            r = d; /* d = a b */
            for (int i = 0; i < n; i++)
                r.v[i] = a.v[i] * b.v[i];
            out = d;
            tex_colour_mul(&out, n, &a, &b);
            bad[1] += !same(&out, &r, sizeof out);
            r = d; /* d = a s, in place */
            for (int i = 0; i < n; i++)
                r.v[i] = d.v[i] * s;
            out = d;
            tex_colour_scale(&out, n, &out, s);
            bad[2] += !same(&out, &r, sizeof out);
            out = d;
            tex_colour_copy(&out, n, &a);
            r = d;
            memcpy(r.v, a.v, n * sizeof *a.v);
            bad[3] += !same(&out, &r, sizeof out);
            if (t % 10 == 0) /* NaN first, or anywhere */
                a.v[t % 20 ? t % n : 0] = NAN;
            float m = tex_colour_max(&a, n), mr = max_ref(&a, n);
            bad[4] += !same(&m, &mr, sizeof m);
        }
    }
    CHECKF(!bad[0], "tex_colour_mmadd: the scalar loop's bits at 3..64 samples (%d differ)", bad[0]);
    CHECKF(!bad[1], "tex_colour_mul: the scalar loop's bits (%d differ)", bad[1]);
    CHECKF(!bad[2], "tex_colour_scale in place: the scalar loop's bits (%d differ)", bad[2]);
    CHECKF(!bad[3], "tex_colour_copy: the first n samples, nothing past them (%d differ)", bad[3]);
    CHECKF(!bad[4], "tex_colour_max: the scalar loop's number, NaN and -0 included (%d differ)",
           bad[4]);
    /* the largest in lane 0 past v[0] (bands 4, 8, 12): main's four lanes once left it out */
    for (int k = 0; k < 7; k++) {
        int n = ns[k], lost = 0;
        for (int at = 4; at < n; at += 4) {
            tex_colour a = {{0}};
            a.v[at] = 5;
            lost += tex_colour_max(&a, n) != 5;
        }
        CHECKF(!lost, "tex_colour_max of %d samples: a largest at a multiple of 4 counts (%d lost)",
               n, lost);
    }
}

static void bands(const tex_colorimetry *cm)
{
    const int ns[] = {1, 3, 7, 8, 15, 16, 17, 64};
    int bad[3] = {0};
    for (int k = 0; k < 8; k++) {
        struct tex_bands b;
        tex_bands_init(&b, ns[k], cm);
        for (int t = 0; t < 300; t++) {
            tex_colour s;
            fill(&s);
            if (t % 3 == 0) /* spectra as the renderer makes them: non-negative */
                for (int i = 0; i < b.n; i++)
                    s.v[i] = fabsf(s.v[i]);
            double xyz[3], ref[3] = {0, 0, 0};
            for (int i = 0; i < b.n; i++)
                for (int c = 0; c < 3; c++)
                    ref[c] += s.v[i] * b.wxyz[i][c];
            tex_bands_xyz(&b, s.v, xyz);
            bad[0] += !same(xyz, ref, sizeof xyz);
            double rgb[3] = {draw(), draw(), draw()};
            float out[TEX_BANDS_MAX], outr[TEX_BANDS_MAX];
            int refl = t & 1;
            float c3[3];
            for (int j = 0; j < 3; j++)
                c3[j] = (float)(b.rgb2c[j][0] * rgb[0] + b.rgb2c[j][1] * rgb[1] +
                                b.rgb2c[j][2] * rgb[2]);
            for (int i = 0; i < b.n; i++) {
                float v = c3[0] * b.basis[0][i] + c3[1] * b.basis[1][i] + c3[2] * b.basis[2][i];
                v = v < 0 ? 0 : v;
                outr[i] = refl && v > 1 ? 1 : v;
            }
            tex_bands_from_rgb(&b, rgb, refl, out);
            bad[1] += !same(out, outr, b.n * sizeof *out);
        }
    }
    /* the gamut map's smallest and largest channel: fmin's and fmax's, NaN included */
    const double odd[][3] = {{NAN, -0.2, 0.5}, {-0.2, NAN, 0.5}, {0.4, 0.5, NAN},
                             {NAN, NAN, -0.1}, {-0.0, 0.0, 0.3}, {1.5, -0.3, 0.2},
                             {0.2, 1.7, NAN}, {-0.1, -0.2, 2.0}};
    for (int k = 0; k < 8; k++)
        for (int g = 0; g < 2; g++) {
            double r[3], e[3];
            memcpy(r, odd[k], sizeof r);
            memcpy(e, odd[k], sizeof e);
            tex_gamut_map(r, g ? TEX_GAMUT_DESATURATE : TEX_GAMUT_CHROMA);
            /* tex_gamut_map as main wrote it, with libm's fmin and fmax */
            double y = 0.2126729 * e[0] + 0.7151522 * e[1] + 0.0721750 * e[2];
            if (!(y > 0)) {
                e[0] = e[1] = e[2] = 0;
            } else if (y >= 1 && g) {
                e[0] = e[1] = e[2] = 1;
            } else {
                double lo = fmin(e[0], fmin(e[1], e[2]));
                if (lo < 0)
                    for (int i = 0; i < 3; i++)
                        e[i] = y + y / (y - lo) * (e[i] - y);
                if (!g) {
                    for (int i = 0; i < 3; i++)
                        e[i] = e[i] < 0 ? 0 : e[i];
                } else {
                    double hi = fmax(e[0], fmax(e[1], e[2]));
                    if (hi > 1)
                        for (int i = 0; i < 3; i++)
                            e[i] = y + (1 - y) / (hi - y) * (e[i] - y);
                    for (int i = 0; i < 3; i++)
                        e[i] = e[i] < 0 ? 0 : e[i] > 1 ? 1 : e[i];
                }
            }
            bad[2] += !same(r, e, sizeof r);
        }
    CHECKF(!bad[0], "tex_bands_xyz: X, Y, Z summed band by band in double, bit for bit at 1..64 "
           "bands (%d differ)", bad[0]);
    CHECKF(!bad[1], "tex_bands_from_rgb: the scalar loop's bits (%d differ)", bad[1]);
    CHECKF(!bad[2], "tex_gamut_map: libm's fmin and fmax, NaN channels included (%d differ)",
           bad[2]);
}

int main(void)
{
    colour_ops();
    tex_colorimetry cm;
    int rc = tex_colorimetry_load(&cm, NULL);
    CHECKF(rc == 0, "CIE tables load (%s)", rc ? tex_errmsg() : "ok");
    if (rc == 0)
        bands(&cm);
    return unit_done();
}
