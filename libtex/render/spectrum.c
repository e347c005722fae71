/* spectrum.c - the spectral colour model: curves, Hall bands, CIE, sRGB */
#include "render/spectrum.h"

#include "base/error.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COLORD_DIR "/usr/share/colord"

void tex_curve_constant(tex_curve *c, double v)
{
    for (int i = 0; i < TEX_CURVE_N; i++)
        c->v[i] = (float)v;
}

int tex_curve_from_table(tex_curve *c, const double *wl, const double *val, int n)
{
    if (n < 1)
        return tex_usage_error("spectrum table is empty");
    for (int j = 0; j < n; j++) {
        if (!(wl[j] >= 0) || !isfinite(wl[j]))
            return tex_usage_error("spectrum table: wavelength %g is not a finite number >= 0",
                                   wl[j]);
        if (!isfinite((float)val[j])) /* the curve holds floats */
            return tex_usage_error("spectrum table: value %g at %g nm is not a finite float "
                                   "(|v| <= 3.4e38)", val[j], wl[j]);
        if (j > 0 && !(wl[j] > wl[j - 1]))
            return tex_usage_error("spectrum table: wavelengths not increasing (%g after %g)",
                                   wl[j], wl[j - 1]);
    }
    int j = 0;
    for (int i = 0; i < TEX_CURVE_N; i++) {
        double l = TEX_LAMBDA_MIN + i;
        if (l <= wl[0]) {
            c->v[i] = (float)val[0];
            continue;
        }
        if (l >= wl[n - 1]) {
            c->v[i] = (float)val[n - 1];
            continue;
        }
        while (wl[j + 1] < l)
            j++;
        double t = (l - wl[j]) / (wl[j + 1] - wl[j]);
        c->v[i] = (float)(val[j] + t * (val[j + 1] - val[j]));
    }
    return 0;
}

static double planck(double nm, double kelvin)
{
    const double h = 6.62607015e-34, cl = 299792458.0, kb = 1.380649e-23;
    double l = nm * 1e-9;
    return 2 * h * cl * cl / (pow(l, 5) * expm1(h * cl / (l * kb * kelvin)));
}

int tex_curve_blackbody(tex_curve *c, double kelvin)
{
    if (!(kelvin >= 100 && kelvin <= 1e6))
        return tex_usage_error("blackbody temperature %g K outside [100, 1e6]", kelvin);
    double ref = planck(560, kelvin);
    for (int i = 0; i < TEX_CURVE_N; i++)
        c->v[i] = (float)(planck(TEX_LAMBDA_MIN + i, kelvin) / ref);
    return 0;
}

double tex_curve_at(const tex_curve *c, double nm)
{
    double x = nm - TEX_LAMBDA_MIN;
    if (x <= 0)
        return c->v[0];
    if (x >= TEX_CURVE_N - 1)
        return c->v[TEX_CURVE_N - 1];
    int i = (int)x;
    double t = x - i;
    return c->v[i] + t * (c->v[i + 1] - c->v[i]);
}

/* Integral of the piecewise-linear curve from TEX_LAMBDA_MIN to nm (clamped to the range). */
static double cumulative(const tex_curve *c, double nm)
{
    double x = nm - TEX_LAMBDA_MIN;
    if (x <= 0)
        return 0;
    if (x > TEX_CURVE_N - 1)
        x = TEX_CURVE_N - 1;
    int i = (int)x;
    double s = 0;
    for (int j = 0; j < i; j++)
        s += 0.5 * (c->v[j] + c->v[j + 1]);
    double t = x - i;
    if (t > 0) {
        double vt = c->v[i] + t * (c->v[i + 1] - c->v[i]);
        s += 0.5 * t * (c->v[i] + vt);
    }
    return s;
}

double tex_curve_mean(const tex_curve *c, double a, double b)
{
    if (!(b > a))
        return tex_curve_at(c, a);
    return (cumulative(c, b) - cumulative(c, a)) / (b - a);
}

/* ---- colord-data IT8 files ---- */

int tex_curve_read_colord(tex_curve *c, const char *path, int set)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return tex_error("%s: %s (the CIE tables come from Debian's colord-data package)", path,
                         strerror(errno));
    char line[16384];
    double start = -1, end = -1;
    long bands = -1, sets = 1;
    int lineno = 0, in_data = 0, row = 0, done = 0, rc = 0;
    while (!done && fgets(line, sizeof line, f)) {
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) {
            rc = tex_error("%s:%d: line too long", path, lineno);
            break;
        }
        char key[64];
        if (!in_data) {
            if (sscanf(line, "%63s", key) != 1)
                continue;
            if (!strcmp(key, "SPECTRAL_START_NM"))
                start = strtod(line + strlen("SPECTRAL_START_NM"), NULL);
            else if (!strcmp(key, "SPECTRAL_END_NM"))
                end = strtod(line + strlen("SPECTRAL_END_NM"), NULL);
            else if (!strcmp(key, "SPECTRAL_BANDS"))
                bands = strtol(line + strlen("SPECTRAL_BANDS"), NULL, 10);
            else if (!strcmp(key, "NUMBER_OF_SETS"))
                sets = strtol(line + strlen("NUMBER_OF_SETS"), NULL, 10);
            else if (!strcmp(key, "BEGIN_DATA")) {
                if (!(start >= 0 && end > start && bands >= 2 && bands <= 100000)) {
                    rc = tex_error("%s:%d: missing or bad SPECTRAL_START_NM/END_NM/BANDS", path,
                                   lineno);
                    break;
                }
                if (set < 0 || set >= sets) {
                    rc = tex_error("%s:%d: no data set %d (the file has %ld)", path, lineno,
                                   set, sets);
                    break;
                }
                in_data = 1;
            }
            continue;
        }
        if (sscanf(line, "%63s", key) == 1 && !strcmp(key, "END_DATA")) {
            rc = tex_error("%s:%d: data set %d missing", path, lineno, set);
            break;
        }
        if (row++ != set)
            continue;
        double *wl = malloc(bands * sizeof *wl), *val = malloc(bands * sizeof *val);
        if (!wl || !val) {
            free(wl);
            free(val);
            rc = tex_error("out of memory");
            break;
        }
        char *p = line;
        for (long i = 0; i < bands && rc == 0; i++) {
            char *e;
            errno = 0;
            val[i] = strtod(p, &e);
            if (e == p || errno || !isfinite(val[i]))
                rc = tex_error("%s:%d: value %ld of %ld missing or not a number", path, lineno,
                               i + 1, bands);
            p = e;
            wl[i] = start + (end - start) * i / (bands - 1);
        }
        if (rc == 0 && tex_curve_from_table(c, wl, val, (int)bands) < 0)
            rc = tex_error("%s:%d: %s", path, lineno, tex_errmsg());
        free(wl);
        free(val);
        done = 1;
    }
    if (rc == 0 && !done)
        rc = tex_error("%s: no BEGIN_DATA section with set %d", path, set);
    fclose(f);
    return rc;
}

static const char *colord_dir(const char *dir)
{
    if (dir)
        return dir;
    const char *e = getenv("TEXTURA_COLORD");
    return e && *e ? e : COLORD_DIR;
}

int tex_colorimetry_load(tex_colorimetry *cm, const char *dir)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/cmf/CIE1931-2deg-XYZ.cmf", colord_dir(dir));
    if (tex_curve_read_colord(&cm->x, path, 0) < 0 || tex_curve_read_colord(&cm->y, path, 1) < 0 ||
        tex_curve_read_colord(&cm->z, path, 2) < 0)
        return -1;
    return tex_illuminant(&cm->d65, "D65", dir);
}

int tex_illuminant(tex_curve *c, const char *name, const char *dir)
{
    if (!strcmp(name, "E")) {
        tex_curve_constant(c, 1);
        return 0;
    }
    if (!strncmp(name, "blackbody:", 10)) {
        char *e;
        double k = strtod(name + 10, &e);
        if (e == name + 10 || *e)
            return tex_usage_error("illuminant '%s': expected blackbody:KELVIN", name);
        return tex_curve_blackbody(c, k);
    }
    for (const char *p = name; *p; p++)
        if (!((*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9')))
            return tex_usage_error("illuminant '%s': expected D65, A, E, another CIE name of "
                                   "colord-data (D50, F2, ...) or blackbody:KELVIN",
                                   name);
    char path[4096];
    snprintf(path, sizeof path, "%s/illuminant/CIE-%s.sp", colord_dir(dir), name);
    return tex_curve_read_colord(c, path, 0);
}

/* ---- bands ---- */

static double sig(double t)
{
    return 1 / (1 + exp(-t));
}

static void basis_curves(tex_curve c[3])
{
    for (int i = 0; i < TEX_CURVE_N; i++) {
        double l = TEX_LAMBDA_MIN + i;
        double blue = 1 - sig((l - 490) / 12), red = sig((l - 590) / 12);
        c[0].v[i] = (float)red;
        c[1].v[i] = (float)(1 - blue - red);
        c[2].v[i] = (float)blue;
    }
}

static int invert3(const double m[3][3], double r[3][3])
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (fabs(det) < 1e-12)
        return -1;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
    return 0;
}

/* XYZ -> RGB for the sRGB primaries and a given white XYZ (SMPTE RP 177):
 * the columns of RGB -> XYZ are the primaries' xyz scaled so that (1,1,1) maps to white. */
static int primaries_matrix(const double white[3], double xyz2rgb[3][3])
{
    const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    double p[3][3], pi[3][3], m[3][3];
    for (int j = 0; j < 3; j++) {
        p[0][j] = xy[j][0] / xy[j][1];
        p[1][j] = 1;
        p[2][j] = (1 - xy[j][0] - xy[j][1]) / xy[j][1];
    }
    if (invert3(p, pi) < 0)
        return -1;
    double s[3];
    for (int j = 0; j < 3; j++)
        s[j] = pi[j][0] * white[0] + pi[j][1] * white[1] + pi[j][2] * white[2];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m[i][j] = p[i][j] * s[j];
    return invert3(m, xyz2rgb);
}

int tex_bands_init(struct tex_bands *b, int n, const tex_colorimetry *cm)
{
    if (n < 1 || n > TEX_BANDS_MAX)
        return tex_usage_error("spectral samples %d outside [1, %d]", n, TEX_BANDS_MAX);
    memset(b, 0, sizeof *b);
    b->n = n;
    b->width = (double)(TEX_LAMBDA_MAX - TEX_LAMBDA_MIN) / n;
    double ynorm = (TEX_LAMBDA_MAX - TEX_LAMBDA_MIN) *
                   tex_curve_mean(&cm->y, TEX_LAMBDA_MIN, TEX_LAMBDA_MAX);
    if (!(ynorm > 0))
        return tex_error("CIE ybar integrates to %g", ynorm);
    const tex_curve *cmf[3] = {&cm->x, &cm->y, &cm->z};
    for (int i = 0; i < n; i++) {
        double lo = TEX_LAMBDA_MIN + i * b->width, hi = lo + b->width;
        b->centre[i] = (float)(0.5 * (lo + hi));
        for (int k = 0; k < 3; k++)
            b->wxyz[i][k] = (float)(tex_curve_mean(cmf[k], lo, hi) * b->width / ynorm);
    }
    float d65[TEX_BANDS_MAX];
    if (tex_bands_light(b, &cm->d65, d65) < 0)
        return tex_error("D65 has no luminance");
    double white[3];
    tex_bands_xyz(b, d65, white);
    if (primaries_matrix(white, b->xyz2rgb) < 0)
        return tex_error("degenerate white point");
    /* The RGB basis, its colours under D65 (Y = 1), and M^-1. */
    tex_curve basis[3];
    basis_curves(basis);
    double m[3][3];
    for (int j = 0; j < 3; j++) {
        float s[TEX_BANDS_MAX];
        tex_bands_sample(b, &basis[j], b->basis[j]);
        for (int i = 0; i < n; i++)
            s[i] = b->basis[j][i] * d65[i];
        double rgb[3];
        tex_bands_to_rgb(b, s, TEX_GAMUT_NONE, rgb);
        for (int k = 0; k < 3; k++)
            m[k][j] = rgb[k];
    }
    if (invert3(m, b->rgb2c) < 0)
        return tex_error("spectral samples %d: too few to represent RGB colours", n);
    return 0;
}

void tex_bands_sample(const struct tex_bands *b, const tex_curve *c, float *out)
{
    for (int i = 0; i < b->n; i++) {
        double lo = TEX_LAMBDA_MIN + i * b->width;
        out[i] = (float)tex_curve_mean(c, lo, lo + b->width);
    }
}

int tex_bands_light(const struct tex_bands *b, const tex_curve *c, float *out)
{
    tex_bands_sample(b, c, out);
    double xyz[3];
    tex_bands_xyz(b, out, xyz);
    if (!(xyz[1] > 0))
        return -1;
    for (int i = 0; i < b->n; i++)
        out[i] = (float)(out[i] / xyz[1]);
    return 0;
}

/* tex_bands_xyz over n bands: X, Y and Z side by side in lanes, each summed band by band
 * as ever (three scalar chains were once per sample of a spectral render, its largest cost
 * after shading) */
static inline void bands_xyz(const struct tex_bands *b, int n, const float *s, double xyz[3])
{
    typedef float f4 __attribute__((vector_size(16)));
    typedef double d2 __attribute__((vector_size(16)));
    d2 xy = {0, 0};
    double z = 0;
    for (int i = 0; i < n; i++) {
        f4 w;
        memcpy(&w, b->wxyz[i], sizeof w);
        f4 p = w * s[i]; /* the float products s[i] * wxyz[i][k] */
        xy += __builtin_convertvector(__builtin_shufflevector(p, p, 0, 1), d2);
        z += p[2];
    }
    xyz[0] = xy[0];
    xyz[1] = xy[1];
    xyz[2] = z;
}

/* The default band count unrolled: a loop of constant length */
void tex_bands_xyz(const struct tex_bands *b, const float *s, double xyz[3])
{
    if (b->n == TEX_BANDS_DEFAULT)
        bands_xyz(b, TEX_BANDS_DEFAULT, s, xyz);
    else
        bands_xyz(b, b->n, s, xyz);
}

static inline void bands_from_rgb(const struct tex_bands *b, int n, const double rgb[3],
                                  int reflectance, float *out)
{
    /* per hit point in the renderer: single precision, so the loop vectorises */
    float c[3];
    for (int j = 0; j < 3; j++)
        c[j] = (float)(b->rgb2c[j][0] * rgb[0] + b->rgb2c[j][1] * rgb[1] +
                       b->rgb2c[j][2] * rgb[2]);
    float hi = reflectance ? 1.0f : INFINITY;
#pragma omp simd
    for (int i = 0; i < n; i++) {
        float v = c[0] * b->basis[0][i] + c[1] * b->basis[1][i] + c[2] * b->basis[2][i];
        v = v < 0 ? 0 : v;
        out[i] = v > hi ? hi : v;
    }
}

void tex_bands_from_rgb(const struct tex_bands *b, const double rgb[3], int reflectance,
                        float *out)
{
    if (b->n == TEX_BANDS_DEFAULT)
        bands_from_rgb(b, TEX_BANDS_DEFAULT, rgb, reflectance, out);
    else
        bands_from_rgb(b, b->n, rgb, reflectance, out);
}

void tex_bands_to_rgb(const struct tex_bands *b, const float *s, enum tex_gamut g,
                      double rgb[3])
{
    double xyz[3];
    tex_bands_xyz(b, s, xyz);
    for (int i = 0; i < 3; i++)
        rgb[i] = b->xyz2rgb[i][0] * xyz[0] + b->xyz2rgb[i][1] * xyz[1] + b->xyz2rgb[i][2] * xyz[2];
    tex_gamut_map(rgb, g);
}

/* ---- colour spaces ---- */

void tex_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
    double x = xyz[0], y = xyz[1], z = xyz[2];
    rgb[0] = 3.2404542 * x - 1.5371385 * y - 0.4985314 * z;
    rgb[1] = -0.9692660 * x + 1.8760108 * y + 0.0415560 * z;
    rgb[2] = 0.0556434 * x - 0.2040259 * y + 1.0572252 * z;
}

void tex_linear_srgb_to_xyz(const double rgb[3], double xyz[3])
{
    double r = rgb[0], g = rgb[1], b = rgb[2];
    xyz[0] = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    xyz[1] = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    xyz[2] = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
}

/* fmin and fmax (the number where one is NaN) without libm's call */
static inline double min_num(double a, double b)
{
    return a < b || b != b ? a : b;
}

static inline double max_num(double a, double b)
{
    return a > b || b != b ? a : b;
}

void tex_gamut_map(double rgb[3], enum tex_gamut g)
{
    if (g == TEX_GAMUT_NONE)
        return;
    if (g == TEX_GAMUT_CLIP) {
        for (int i = 0; i < 3; i++)
            rgb[i] = rgb[i] < 0 ? 0 : rgb[i] > 1 ? 1 : rgb[i];
        return;
    }
    double y = 0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2];
    if (!(y > 0)) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    if (y >= 1 && g == TEX_GAMUT_DESATURATE) {
        rgb[0] = rgb[1] = rgb[2] = 1;
        return;
    }
    double lo = min_num(rgb[0], min_num(rgb[1], rgb[2]));
    if (lo < 0) { /* toward grey until the lowest channel reaches 0 */
        double t = y / (y - lo);
        for (int i = 0; i < 3; i++)
            rgb[i] = y + t * (rgb[i] - y);
    }
    if (g == TEX_GAMUT_CHROMA) {
        for (int i = 0; i < 3; i++)
            rgb[i] = rgb[i] < 0 ? 0 : rgb[i];
        return;
    }
    double hi = max_num(rgb[0], max_num(rgb[1], rgb[2]));
    if (hi > 1) { /* then until the highest reaches 1 */
        double t = (1 - y) / (hi - y);
        for (int i = 0; i < 3; i++)
            rgb[i] = y + t * (rgb[i] - y);
    }
    for (int i = 0; i < 3; i++) /* rounding */
        rgb[i] = rgb[i] < 0 ? 0 : rgb[i] > 1 ? 1 : rgb[i];
}
