/* test_spectrum.c - Hall bands, CIE integration, white balance, gamut, RGB <-> spectrum */
#include "base/error.h"
#include "render/spectrum.h"
#include "unit.h"

#include <math.h>
#include <string.h>

static void chroma(const double xyz[3], double *x, double *y)
{
    double s = xyz[0] + xyz[1] + xyz[2];
    *x = xyz[0] / s;
    *y = xyz[1] / s;
}

int main(void)
{
    tex_colorimetry cm;
    int rc = tex_colorimetry_load(&cm, NULL);
    CHECKF(rc == 0, "CIE 1931 tables and D65 load from colord-data (%s)",
           rc ? tex_errmsg() : "ok");
    if (rc)
        return unit_done();
    CHECK(fabs(tex_curve_at(&cm.y, 555) - 1) < 1e-6 && fabs(tex_curve_at(&cm.x, 600) - 1.0622) < 1e-6,
          "matching functions read correctly (ybar(555) = 1, xbar(600) = 1.0622)");

    const int ns[] = {1, 3, 16, 64};
    struct tex_bands b;
    for (int i = 0; i < 4; i++) {
        tex_bands_init(&b, ns[i], &cm);
        float s[TEX_BANDS_MAX];
        tex_curve e;
        tex_curve_constant(&e, 1);
        tex_bands_sample(&b, &e, s);
        double xyz[3], x, y;
        tex_bands_xyz(&b, s, xyz);
        chroma(xyz, &x, &y);
        CHECKF(fabs(x - 1.0 / 3) < 2e-3 && fabs(y - 1.0 / 3) < 2e-3 && fabs(xyz[1] - 1) < 1e-6,
               "%d bands: equal-energy spectrum gives x = %.4f, y = %.4f, Y = %.4f", ns[i], x, y,
               xyz[1]);
    }

    CHECK(tex_bands_init(&b, 0, &cm) < 0 && tex_errkind() == TEX_ERR_USAGE &&
              strstr(tex_errmsg(), "[1, 64]"),
          "0 spectral samples is a usage error naming the range");
    CHECK(tex_bands_init(&b, 10000, &cm) < 0 && tex_errkind() == TEX_ERR_USAGE,
          "10000 spectral samples is a usage error");

    tex_bands_init(&b, 16, &cm);
    CHECK(b.n == 16 && fabs(b.centre[0] - 392.5) < 1e-4 && fabs(b.width - 25) < 1e-9,
          "default 16 bands of 25 nm from 380 nm");
    /* Hall's band means: a ramp's mean is its value at the band centre; a step's is the
     * fraction of the band it covers. */
    tex_curve ramp, step;
    double wl[2] = {380, 780}, v[2] = {0, 4};
    tex_curve_from_table(&ramp, wl, v, 2);
    double wl2[4] = {380, 399, 400, 780}, v2[4] = {0, 0, 1, 1};
    tex_curve_from_table(&step, wl2, v2, 4);
    float s[TEX_BANDS_MAX], s2[TEX_BANDS_MAX];
    tex_bands_sample(&b, &ramp, s);
    tex_bands_sample(&b, &step, s2);
    CHECKF(fabs(s[3] - 0.01 * (b.centre[3] - 380)) < 1e-5 && fabs(s2[0] - 5.5 / 25) < 1e-6,
           "band means over 1 nm data (ramp %.4f, step %.4f)", s[3], s2[0]);

    /* D65's chromaticity, and a white diffuse reflector under D65 is neutral. */
    float d65[TEX_BANDS_MAX], a[TEX_BANDS_MAX];
    CHECK(tex_bands_light(&b, &cm.d65, d65) == 0, "D65 normalised to Y = 1");
    double xyz[3], rgb[3], x, y;
    tex_bands_xyz(&b, d65, xyz);
    chroma(xyz, &x, &y);
    CHECKF(fabs(x - 0.3127) < 2e-3 && fabs(y - 0.3290) < 2e-3, "D65 white point (%.4f, %.4f)",
           x, y);
    for (int k = 0; k < 2; k++) {
        double rho = k ? 0.5 : 1;
        float out[TEX_BANDS_MAX];
        for (int i = 0; i < b.n; i++)
            out[i] = (float)(rho * d65[i]);
        tex_bands_to_rgb(&b, out, TEX_GAMUT_NONE, rgb);
        double mx = fmax(rgb[0], fmax(rgb[1], rgb[2])), mn = fmin(rgb[0], fmin(rgb[1], rgb[2]));
        CHECKF(mx - mn < 1e-4 && fabs(rgb[1] - rho) < 1e-4,
               "diffuse reflector %.1f under D65 is neutral grey (%.4f %.4f %.4f)", rho, rgb[0],
               rgb[1], rgb[2]);
    }
    tex_curve ca;
    CHECK(tex_illuminant(&ca, "A", NULL) == 0 && tex_bands_light(&b, &ca, a) == 0,
          "illuminant A from colord-data");
    tex_bands_to_rgb(&b, a, TEX_GAMUT_NONE, rgb);
    CHECKF(rgb[0] > 1.2 * rgb[1] && rgb[1] > 1.5 * rgb[2],
           "a white surface under illuminant A is orange (%.3f %.3f %.3f)", rgb[0], rgb[1],
           rgb[2]);
    tex_curve bb;
    tex_curve_blackbody(&bb, 2856);
    double dmax = 0;
    for (int i = 0; i < TEX_CURVE_N; i++)
        dmax = fmax(dmax, fabs(bb.v[i] - ca.v[i] / tex_curve_at(&ca, 560)) / bb.v[i]);
    CHECKF(dmax < 0.02, "blackbody at 2856 K matches CIE illuminant A (%.4f)", dmax);
    tex_curve_blackbody(&bb, 10000);
    tex_bands_light(&b, &bb, s);
    tex_bands_to_rgb(&b, s, TEX_GAMUT_NONE, rgb);
    CHECK(rgb[2] > rgb[0], "a 10000 K blackbody is bluish");
    CHECK(tex_curve_blackbody(&bb, 0) < 0 && tex_illuminant(&bb, "D65;", NULL) < 0 &&
              tex_illuminant(&bb, "blackbody:x", NULL) < 0,
          "bad blackbody temperatures and illuminant names are errors");
    CHECK(tex_illuminant(&bb, "NOPE", NULL) < 0 && strstr(tex_errmsg(), "CIE-NOPE.sp"),
          "an unknown illuminant names the missing file");
    CHECK(tex_colorimetry_load(&cm, "/nonexistent") < 0 && strstr(tex_errmsg(), "colord-data"),
          "missing CIE tables: the message names the colord-data package");
    tex_colorimetry_load(&cm, NULL);

    /* RGB -> spectrum -> RGB under D65. */
    const double cols[][3] = {{0.5, 0.3, 0.2}, {0.18, 0.18, 0.18}, {0.2, 0.6, 0.3},
                              {0.1, 0.2, 0.7}, {1, 1, 1}};
    for (int c = 0; c < 5; c++) {
        float r[TEX_BANDS_MAX], lit[TEX_BANDS_MAX];
        tex_bands_from_rgb(&b, cols[c], 1, r);
        for (int i = 0; i < b.n; i++)
            lit[i] = r[i] * d65[i];
        tex_bands_to_rgb(&b, lit, TEX_GAMUT_NONE, rgb);
        double err = fmax(fabs(rgb[0] - cols[c][0]),
                          fmax(fabs(rgb[1] - cols[c][1]), fabs(rgb[2] - cols[c][2])));
        double flat = 0;
        for (int i = 1; i < b.n; i++)
            flat = fmax(flat, fabs(r[i] - r[0]));
        CHECKF(err < 2e-3, "rgb (%.2f %.2f %.2f) -> spectrum -> (%.4f %.4f %.4f)", cols[c][0],
               cols[c][1], cols[c][2], rgb[0], rgb[1], rgb[2]);
        if (cols[c][0] == cols[c][1] && cols[c][1] == cols[c][2])
            CHECKF(flat < 1e-4, "grey %.2f becomes a flat spectrum", cols[c][0]);
    }

    /* Gamut mapping. */
    double in[3] = {1.2, 0.4, -0.2}, ylum = 0.2126729 * 1.2 + 0.7151522 * 0.4 - 0.072175 * 0.2;
    double g[3] = {in[0], in[1], in[2]};
    tex_gamut_map(g, TEX_GAMUT_DESATURATE);
    double ly = 0.2126729 * g[0] + 0.7151522 * g[1] + 0.072175 * g[2];
    CHECKF(fabs(ly - ylum) < 1e-6 && g[0] <= 1 && g[2] >= 0 && g[0] > g[1] && g[1] > g[2],
           "desaturation keeps luminance %.4f and the hue order (%.3f %.3f %.3f)", ylum, g[0],
           g[1], g[2]);
    double cl[3] = {in[0], in[1], in[2]};
    tex_gamut_map(cl, TEX_GAMUT_CLIP);
    CHECK(cl[0] == 1 && cl[1] == 0.4 && cl[2] == 0, "clipping clamps each channel");
    double w[3] = {3, 2, 2};
    tex_gamut_map(w, TEX_GAMUT_DESATURATE);
    CHECK(w[0] == 1 && w[1] == 1 && w[2] == 1, "brighter than white becomes white");
    double inside[3] = {0.3, 0.5, 0.7}, keep[3] = {0.3, 0.5, 0.7};
    tex_gamut_map(inside, TEX_GAMUT_DESATURATE);
    CHECK(!memcmp(inside, keep, sizeof keep), "colours inside the gamut are left alone");

    double wp[3] = {0.95047, 1, 1.08883};
    tex_xyz_to_linear_srgb(wp, rgb);
    CHECKF(fabs(rgb[0] - 1) < 1e-4 && fabs(rgb[1] - 1) < 1e-4 && fabs(rgb[2] - 1) < 1e-4,
           "the sRGB matrix maps the D65 white point to (1,1,1) (%.5f %.5f %.5f)", rgb[0], rgb[1],
           rgb[2]);
    double back[3], xyz2[3] = {0.3, 0.4, 0.5};
    tex_xyz_to_linear_srgb(xyz2, rgb);
    tex_linear_srgb_to_xyz(rgb, back);
    CHECK(fabs(back[0] - 0.3) < 1e-6 && fabs(back[2] - 0.5) < 1e-6,
          "XYZ <-> linear sRGB matrices are inverse");

    double badwl[3] = {400, 390, 500}, badv[3] = {1, 1, 1};
    CHECK(tex_curve_from_table(&bb, badwl, badv, 3) < 0 && tex_errkind() == TEX_ERR_USAGE,
          "unsorted wavelengths are rejected");
    badwl[0] = -5;
    badwl[1] = 390;
    CHECK(tex_curve_from_table(&bb, badwl, badv, 3) < 0, "negative wavelengths are rejected");
    return unit_done();
}
