/* test_matdb.c - the materials database: parsing, errors, metal colours */
#include "base/error.h"
#include "render/fresnel.h"
#include "render/matdb.h"
#include "unit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fails_with(const char *text, const char *want)
{
    struct tex_matdb db;
    int rc = tex_matdb_parse(&db, text, "t.txt");
    int ok = rc < 0 && tex_errkind() == TEX_ERR_USAGE && strstr(tex_errmsg(), want);
    if (!ok)
        printf("# got rc=%d '%s', wanted '%s'\n", rc, rc < 0 ? tex_errmsg() : "", want);
    if (rc == 0)
        tex_matdb_free(&db);
    return ok;
}

/* Normal-incidence colour of a conductor under D65, linear sRGB. */
static void metal_rgb(const struct tex_bands *b, const tex_colorimetry *cm,
                      const struct tex_matdb_entry *m, double rgb[3])
{
    float n[TEX_BANDS_MAX], k[TEX_BANDS_MAX], f[TEX_BANDS_MAX], d65[TEX_BANDS_MAX];
    tex_bands_sample(b, &m->n, n);
    tex_bands_sample(b, &m->k, k);
    tex_bands_light(b, &cm->d65, d65);
    tex_fresnel_conductor_n(1, 1, n, k, b->n, f);
    for (int i = 0; i < b->n; i++)
        f[i] *= d65[i];
    tex_bands_to_rgb(b, f, TEX_GAMUT_NONE, rgb);
}

int main(void)
{
    char path[4096];
    struct tex_matdb db;
    unit_top_path("patterns/materials.txt", path, sizeof path);
    int rc = tex_matdb_read(&db, path);
    CHECKF(rc == 0, "the shipped database reads (%s)", rc ? tex_errmsg() : "ok");
    if (rc)
        return unit_done();
    const char *names[] = {"gold", "silver", "copper", "aluminium", "stainless", "bk7"};
    for (int i = 0; i < 6; i++) {
        const struct tex_matdb_entry *m = tex_matdb_find(&db, names[i]);
        CHECKF(m && m->source && *m->source, "%s is there with its source cited", names[i]);
    }
    const struct tex_matdb_entry *bk7 = tex_matdb_find(&db, "bk7");
    double nd = tex_curve_at(&bk7->n, 587.6);
    CHECKF(bk7->kind == TEX_DIELECTRIC && fabs(nd - 1.5168) < 5e-4 &&
               tex_curve_at(&bk7->n, 400) > tex_curve_at(&bk7->n, 700),
           "BK7 from Sellmeier: n_d = %.4f, normal dispersion", nd);
    CHECK(!tex_matdb_find(&db, "unobtainium") && tex_errkind() == TEX_ERR_USAGE &&
              strstr(tex_errmsg(), "unobtainium") && strstr(tex_errmsg(), "gold"),
          "an unknown material is a usage error listing the known ones");

    tex_colorimetry cm;
    struct tex_bands b;
    if (tex_colorimetry_load(&cm, NULL) == 0 && tex_bands_init(&b, 16, &cm) == 0) {
        double rgb[3];
        metal_rgb(&b, &cm, tex_matdb_find(&db, "gold"), rgb);
        CHECKF(rgb[0] > rgb[1] && rgb[1] > 1.3 * rgb[2] && rgb[0] > 0.7,
               "gold reflects yellow (%.3f %.3f %.3f)", rgb[0], rgb[1], rgb[2]);
        metal_rgb(&b, &cm, tex_matdb_find(&db, "silver"), rgb);
        double mx = fmax(rgb[0], fmax(rgb[1], rgb[2])), mn = fmin(rgb[0], fmin(rgb[1], rgb[2]));
        CHECKF(mn > 0.85 && mx / mn < 1.1, "silver is bright and near-neutral (%.3f %.3f %.3f)",
               rgb[0], rgb[1], rgb[2]);
        metal_rgb(&b, &cm, tex_matdb_find(&db, "copper"), rgb);
        CHECKF(rgb[0] > 1.3 * rgb[1] && rgb[1] > rgb[2], "copper is reddish (%.3f %.3f %.3f)",
               rgb[0], rgb[1], rgb[2]);
        metal_rgb(&b, &cm, tex_matdb_find(&db, "stainless"), rgb);
        mx = fmax(rgb[0], fmax(rgb[1], rgb[2]));
        mn = fmin(rgb[0], fmin(rgb[1], rgb[2]));
        CHECKF(mx < 0.75 && mx / mn < 1.15, "stainless is a darker near-neutral (%.3f %.3f %.3f)",
               rgb[0], rgb[1], rgb[2]);
    } else {
        CHECKF(0, "colorimetry: %s", tex_errmsg());
    }
    tex_matdb_free(&db);

    CHECK(fails_with("material x conductor\nnk 500 1 1\nnk 450 1 1\nend\n", "t.txt:3:"),
          "unsorted wavelengths: file:line");
    /* found by fuzz_matdb: finite doubles past a float's range made infinite curves */
    CHECK(fails_with("material x conductor\nnk 400 1e300 1\nnk 500 1 1\nend\n",
                     "not a finite float"),
          "an n past a float's range is refused");
    CHECK(fails_with("material x dielectric\ncauchy 1e200 0\nend\n", "is not > 0"),
          "a formula index past a float's range is refused");
    CHECK(fails_with("material x conductor\nnk -5 1 1\nend\n", "t.txt:2: wavelength"),
          "negative wavelength");
    CHECK(fails_with("material x conductor\nnk 500 1 -0.1\nend\n", "t.txt:2: k"), "k < 0");
    CHECK(fails_with("material x conductor\nnk 500 0 1\nend\n", "t.txt:2: n"), "n <= 0");
    CHECK(fails_with("material x dielectric\nior 0\nend\n", "t.txt:2: ior"), "ior <= 0");
    CHECK(fails_with("material x dielectric\nior -1.5\nend\n", "t.txt:2:"), "negative ior");
    CHECK(fails_with("material x dielectric\ncauchy -1 0\nend\n", "t.txt:3:"),
          "a Cauchy formula giving n <= 0");
    CHECK(fails_with("material x dielectric\nior 1.5\n", "no 'end'"), "missing end");
    CHECK(fails_with("material x conductor\nior 1.5\nend\n", "needs nk"),
          "a conductor without n and k");
    CHECK(fails_with("material x dielectric\nend\n", "no data"), "a material without data");
    CHECK(fails_with("material x metal\nend\n", "t.txt:1:"), "unknown kind");
    CHECK(fails_with("material x dielectric\nfoo 1\nend\n", "unknown keyword 'foo'"),
          "unknown keyword");
    CHECK(fails_with("nk 500 1 1\n", "outside a material"), "data outside a material");
    CHECK(fails_with("material x dielectric\nior 1.5\nend\nmaterial x dielectric\nior 1\nend\n",
                     "t.txt:4: material 'x' defined twice"),
          "duplicate names");
    CHECK(fails_with("material x conductor\nnk 500 1 1x\nend\n", "t.txt:2:"),
          "junk after a number");
    CHECK(fails_with("material x conductor\nnk 500 nan 1\nend\n", "t.txt:2:"), "NaN");
    CHECK(tex_matdb_read(&db, "/nonexistent/materials.txt") < 0 &&
              tex_errkind() == TEX_ERR_RUNTIME,
          "a missing database is a runtime error");

    rc = tex_matdb_parse(&db,
                             "# c\nmaterial w dielectric\nsource me\ncauchy 1.3 0.003\nend\n"
                             "material m conductor\nnk 400 1 2 # row\nnk 700 2 4\nend\n",
                             "ok.txt");
    const struct tex_matdb_entry *m = rc == 0 ? tex_matdb_find(&db, "m") : NULL;
    CHECK(rc == 0 && db.count == 2 && m && fabs(tex_curve_at(&m->k, 550) - 3) < 1e-5 &&
              fabs(tex_curve_at(&m->n, 380) - 1) < 1e-6,
          "a small database parses; n, k interpolate linearly and hold at the ends");
    if (rc == 0)
        tex_matdb_free(&db);
    return unit_done();
}
