/* test_render_ct.c - the spectral colour space and the Cook-Torrance shading model */
#include "render/colour_spectral.h"
#include "base/error.h"
#include "render/fresnel.h"
#include "render/render.h"
#include "render/render_ct.h"
#include "unit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The colour of a highlight: light from (0,0,1) reflected to the mirror direction. */
static void highlight(const struct tex_colour_space *cs, const struct tex_matdb_entry *e,
                      float rgb[3])
{
    struct tex_ct ct;
    tex_ct_init(&ct, cs, e, TEX_FACET_BECKMANN, 0.2, 0, 1);
    struct tex_material mat;
    memset(&mat, 0, sizeof mat);
    mat.ior = 1.5;
    mat.kr = 1;
    tex_ct_material(&mat, &ct);
    float white[3] = {1, 1, 1};
    tex_colour E, out;
    cs->from_rgb(cs, white, TEX_SPECTRUM_ILLUMINANT, &E);
    tex_colour_set(&out, cs->n, 0);
    double s = sin(0.3), c = cos(0.3);
    double N[3] = {0, 0, 1}, V[3] = {s, 0, c}, L[3] = {-s, 0, c};
    mat.model->direct(&mat, N, V, L, &E, cs->n, &out);
    cs->to_rgb(cs, &out, rgb);
}

/* from_rgb remembers its last conversions (per thread): six colours, each converted as
 * reflectance and as illuminant in two spaces of 16 and 8 bands, the four conversions
 * twice over (the second time from memory), the spaces made anew each pass with their
 * band counts swapped (where the last were freed), give the bits of conversions made
 * too far apart to be remembered.
 * Returns the conversions that differed. */
static int remembered_spectra(void)
{
    const float c[6][3] = {{0.8f, 0.2f, 0.1f}, {0.1f, 0.8f, 0.2f}, {0.2f, 0.1f, 0.8f},
                           {0.5f, 0.5f, 0.5f}, {0.08f, 0.08f, 0.08f}, {0.83f, 0.83f, 0.83f}};
    struct tex_colour_space sp[2];
    tex_colour first[2][6][2]; /* [16 or 8 bands][colour][kind] */
    int bad = 0;
    for (int pass = 0; pass < 3; pass++) {
        for (int k = 0; k < 2; k++)
            if (tex_colour_space_spectral(&sp[k], (k + pass) % 2 ? 8 : 16, NULL) < 0)
                return -1;
        for (int kind = 0; pass == 0 && kind < 2; kind++) /* fresh: six apart */
            for (int k = 0; k < 2; k++)
                for (int j = 0; j < 6; j++)
                    sp[k].from_rgb(&sp[k], c[j], kind, &first[sp[k].n == 8][j][kind]);
        for (int j = 0; j < 6; j++)
            for (int i = 0; i < 8; i++) {
                int k = i % 2, kind = i / 2 % 2, b = sp[k].n == 8;
                tex_colour out;
                sp[k].from_rgb(&sp[k], c[j], kind, &out);
                bad += memcmp(out.v, first[b][j][kind].v, sp[k].n * sizeof *out.v) != 0;
            }
        for (int k = 0; k < 2; k++)
            tex_colour_space_spectral_free(&sp[k]);
    }
    return bad;
}

/* direct() adds a Beckmann highlight exactly where its weight w = s pi G' (N.L) is over
 * 1e-12 (G' = tex_ct_geometry), though it decides most of the tiny ones without D's exp:
 * random lights and views over the hemisphere, grazing ones too, on lobes from polished to
 * matte.  Returns the cases whose w lay within a factor 10 of the cut; *wrong counts the
 * highlights added or left out against w. */
static int highlight_cut(const struct tex_colour_space *cs, int *wrong)
{
    struct tex_material mat;
    memset(&mat, 0, sizeof mat);
    tex_ct_material(&mat, NULL);
    mat.ior = 1.5;
    tex_colour_set(&mat.kd, cs->n, 0);
    float w1[3] = {1, 1, 1};
    tex_colour E, out;
    cs->from_rgb(cs, w1, TEX_SPECTRUM_ILLUMINANT, &E);
    const double ms[] = {0.02, 0.05, 0.1, 0.25, 0.6};
    unsigned long x = 12345;
    int near = 0;
    *wrong = 0;
    for (int i = 0; i < 200000; i++) {
        double u[4];
        for (int j = 0; j < 4; j++) {
            x = x * 6364136223846793005ul + 1442695040888963407ul;
            u[j] = (double)(x >> 11) / 9007199254740992.0;
        }
        mat.m = ms[i % 5];
        mat.s = 0.05 + 0.95 * (i % 7) / 6.0;
        /* heights from grazing (u^3 near 0) to overhead */
        double zv = u[0] * u[0] * u[0], zl = u[1] * u[1] * u[1];
        double pv = 2 * M_PI * u[2], pl = 2 * M_PI * u[3];
        double rv = sqrt(1 - zv * zv), rl = sqrt(1 - zl * zl);
        double N[3] = {0, 0, 1}, V[3] = {rv * cos(pv), rv * sin(pv), zv},
               L[3] = {rl * cos(pl), rl * sin(pl), zl};
        tex_colour_set(&out, cs->n, 0);
        mat.model->direct(&mat, N, V, L, &E, cs->n, &out);
        /* ct_direct's steps, in its order */
        double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
        double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        double nh = h[2] / hl, vh = (V[0] * h[0] + V[1] * h[1] + V[2] * h[2]) / hl;
        struct tex_facets fc = {TEX_FACET_BECKMANN, mat.m, 0};
        double w = mat.s * M_PI * tex_ct_geometry(&fc, nh, zv, zl, vh) * zl;
        near += w > 1e-13 && w < 1e-11;
        *wrong += (out.v[0] > 0) != (w > 1e-12);
    }
    return near;
}

/* Reflection and transmission weights, the Fresnel table against the formula, and a
 * surface without model data, under light E */
static void weights(const struct tex_colour_space *cs, struct tex_matdb *db, const tex_colour *E)
{
    struct tex_ct ct;
    struct tex_material mat;
    memset(&mat, 0, sizeof mat);
    mat.ior = 1.5;
    mat.kr = mat.kt = 1;
    tex_ct_init(&ct, cs, tex_matdb_find(db, "bk7"), TEX_FACET_BECKMANN, 0.1, 0, 0.5);
    tex_ct_material(&mat, &ct);
    tex_colour kr, kt, out;
    double worst = 0;
    for (double c = -1; c <= 1; c += 0.05) {
        mat.model->weights(&mat, c, cs->n, &kr, &kt);
        for (int i = 0; i < cs->n; i++)
            worst = fmax(worst, fabs(kr.v[i] + kt.v[i] - 1));
    }
    CHECKF(worst < 1e-6, "glass: Fr + Ft = 1 per band, from both sides (%.2g)", worst);
    mat.model->weights(&mat, 1, cs->n, &kr, &kt);
    CHECKF(fabs(kr.v[8] - 0.042) < 0.003, "BK7 reflects about 4.2%% at normal incidence (%.4f)",
           kr.v[8]);
    mat.model->weights(&mat, -0.3, cs->n, &kr, &kt);
    CHECK(kr.v[0] == 1 && kt.v[0] == 0, "inside glass at a grazing angle: total internal reflection");
    tex_ct_init(&ct, cs, tex_matdb_find(db, "copper"), TEX_FACET_BECKMANN, 0.1, 0, 0.5);
    mat.model->weights(&mat, 0.9, cs->n, &kr, &kt);
    CHECKF(kt.v[0] == 0 && kr.v[cs->n - 1] > kr.v[0] + 0.2,
           "copper: no transmission, reflects more red than blue (%.3f vs %.3f)", kr.v[cs->n - 1],
           kr.v[0]);
    worst = 0;
    for (double c = 0; c <= 1; c += 0.01) {
        mat.model->weights(&mat, c, cs->n, &kr, &kt);
        for (int i = 0; i < cs->n; i++)
            worst = fmax(worst, fabs(kr.v[i] - tex_fresnel_conductor(c, 1, ct.eta.v[i], ct.k.v[i])));
    }
    CHECKF(worst < 1e-5, "copper: the per-spectrum Fresnel equals tex_fresnel_conductor (%.2g)",
           worst);
    /* The renderer's table (tex_ct_tabulate) against the formula, every
     * material of the database (glasses from outside), between and on its steps. */
    static const char *const tabled[] = {"gold",      "silver",    "copper", "aluminium",
                                         "chromium",  "stainless", "bk7",    "dielectric"};
    double worst_table = 0;
    int tables = 0;
    for (size_t m = 0; m < sizeof tabled / sizeof *tabled; m++) {
        const struct tex_matdb_entry *e = tex_matdb_find(db, tabled[m]);
        if (!e || tex_ct_init(&ct, cs, e, TEX_FACET_BECKMANN, 0.1, 0, 0.5) < 0 ||
            tex_ct_tabulate(&ct, cs->n) < 0)
            continue;
        tables += ct.table != NULL;
        for (int j = 0; j <= 4000; j++) {
            double c = j / 4000.0;
            mat.model->weights(&mat, c, cs->n, &kr, &kt);
            for (int i = 0; i < cs->n; i++) {
                double f = ct.conductor ? tex_fresnel_conductor(c, 1, ct.eta.v[i], ct.k.v[i])
                                        : tex_fresnel_dielectric(c, 1, ct.eta.v[i], NULL);
                worst_table = fmax(worst_table, fabs(kr.v[i] - f));
            }
        }
        tex_ct_untabulate(&ct);
    }
    CHECKF(tables == 8 && worst_table < 2e-5,
           "the Fresnel table is within 2e-5 of the formula (%d tables, worst %.2g)", tables,
           worst_table);
    CHECK(tex_ct_init(&ct, cs, NULL, TEX_FACET_BECKMANN, 0, 0, 0.5) < 0 &&
              tex_ct_init(&ct, cs, NULL, TEX_FACET_BECKMANN, 0.2, 0, 1.5) < 0,
          "bad roughness or specular fraction: usage errors");
    tex_ct_material(&mat, NULL);
    mat.model->weights(&mat, 1, cs->n, &kr, &kt);
    tex_colour_set(&out, cs->n, 0);
    double N0[3] = {0, 0, 1};
    mat.model->direct(&mat, N0, N0, N0, E, cs->n, &out);
    CHECKF(fabs(kr.v[0] - 0.04) < 1e-6 && out.v[0] > 0,
           "without model data: a dielectric of the surface's ior (Fr %.4f)", kr.v[0]);
}

int main(void)
{
    struct tex_colour_space cs, rgbcs;
    CHECK(tex_colour_space_spectral(&cs, 0, NULL) < 0 && tex_errkind() == TEX_ERR_USAGE,
          "0 spectral samples: usage error");
    CHECK(tex_colour_space_spectral(&cs, 10000, NULL) < 0 && tex_errkind() == TEX_ERR_USAGE,
          "10000 spectral samples: usage error");
    int rc = tex_colour_space_spectral(&cs, 16, NULL);
    CHECKF(rc == 0 && cs.n == 16 && cs.mode == TEX_COLOUR_SPECTRAL, "16-band colour space (%s)",
           rc ? tex_errmsg() : "ok");
    if (rc)
        return unit_done();
    tex_colour_space_rgb(&rgbcs);

    /* A white diffuse surface under a white (D65) light is neutral. */
    float w[3] = {1, 1, 1}, grey[3] = {0.5f, 0.5f, 0.5f}, rgb[3];
    tex_colour E, kd, out;
    cs.from_rgb(&cs, w, TEX_SPECTRUM_ILLUMINANT, &E);
    cs.from_rgb(&cs, grey, TEX_SPECTRUM_REFLECTANCE, &kd);
    tex_colour_mul(&out, cs.n, &kd, &E);
    cs.to_rgb(&cs, &out, rgb);
    CHECKF(fabs(rgb[0] - 0.5) < 1e-3 && fabs(rgb[1] - 0.5) < 1e-3 && fabs(rgb[2] - 0.5) < 1e-3,
           "grey 0.5 under the white light renders (%.4f %.4f %.4f)", rgb[0], rgb[1], rgb[2]);
    tex_curve a;
    tex_colour la;
    CHECK(tex_illuminant(&a, "A", NULL) == 0 && tex_colour_space_spectral_light(&cs, &a, &la) == 0,
          "illuminant A as a light");
    tex_colour_mul(&out, cs.n, &kd, &la);
    cs.to_rgb(&cs, &out, rgb);
    CHECKF(rgb[0] > rgb[2] * 2, "grey under A is orange (%.3f %.3f %.3f)", rgb[0], rgb[1],
           rgb[2]);
    tex_colour_space_spectral_light(&rgbcs, &a, &la);
    CHECKF(la.v[0] > 2 * la.v[2], "illuminant A in an RGB scene (%.3f %.3f %.3f)", la.v[0],
           la.v[1], la.v[2]);

    char path[4096];
    struct tex_matdb db;
    unit_top_path("patterns/materials.txt", path, sizeof path);
    if (tex_matdb_read(&db, path) < 0) {
        CHECKF(0, "materials: %s", tex_errmsg());
        return unit_done();
    }
    highlight(&cs, tex_matdb_find(&db, "gold"), rgb);
    CHECKF(rgb[0] > rgb[1] && rgb[1] > 1.3 * rgb[2], "spectral gold highlight is yellow (%.3f %.3f %.3f)",
           rgb[0], rgb[1], rgb[2]);
    float g0 = rgb[0];
    highlight(&cs, tex_matdb_find(&db, "silver"), rgb);
    float mx = fmaxf(rgb[0], fmaxf(rgb[1], rgb[2])), mn = fminf(rgb[0], fminf(rgb[1], rgb[2]));
    CHECKF(mn > 0 && mx / mn < 1.1 && mx > g0 * 0.8,
           "spectral silver highlight is neutral (%.3f %.3f %.3f)", rgb[0], rgb[1], rgb[2]);
    highlight(&cs, NULL, rgb);
    CHECKF(rgb[1] > 0 && rgb[1] < 0.2 * g0 && fabs(rgb[0] - rgb[2]) < 0.02 * rgb[1] + 1e-4,
           "a dielectric (ior 1.5) gets a faint white highlight (%.4f %.4f %.4f)", rgb[0], rgb[1],
           rgb[2]);
    highlight(&rgbcs, tex_matdb_find(&db, "gold"), rgb);
    CHECKF(rgb[0] > rgb[1] && rgb[1] > rgb[2], "RGB-mode gold highlight is yellow too (%.3f %.3f %.3f)",
           rgb[0], rgb[1], rgb[2]);
    float again[3];
    highlight(&cs, tex_matdb_find(&db, "gold"), again);
    highlight(&cs, tex_matdb_find(&db, "gold"), rgb);
    CHECK(!memcmp(again, rgb, sizeof rgb), "shading is deterministic");

    weights(&cs, &db, &E);
    int bad = remembered_spectra();
    CHECKF(bad == 0, "remembered RGB-to-spectrum conversions give their own bits, space by "
           "space and kind by kind (%d differ)", bad);
    int wrong, near = highlight_cut(&cs, &wrong);
    CHECKF(wrong == 0 && near > 1000,
           "a highlight where its weight is over 1e-12 and none elsewhere (%d wrong, %d "
           "within 10x of the cut)",
           wrong, near);
    CHECK(tex_shading_find("cook-torrance") == &tex_shading_cook_torrance,
          "the model is found by its scene name");
    tex_matdb_free(&db);
    tex_colour_space_spectral_free(&cs);
    return unit_done();
}
