/* test_palette - palette parsing, lookup, OKLab, round trip, errors, shipped palettes */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/map.h"
#include "base/simd.h"
#include "ops/palette.h"
#include "unit.h"

static tex_palette *parse(const char *s)
{
    return tex_palette_parse(s, strlen(s), "t.pal");
}

static int same4(const float a[4], const float b[4])
{
    return !memcmp(a, b, 4 * sizeof *a);
}

static void check_error(const char *text, const char *want, const char *what)
{
    tex_palette *p = parse(text);
    CHECKF(!p && strstr(tex_errmsg(), want), "%s is refused with '%s' (got '%s')", what, want,
           p ? "(accepted)" : tex_errmsg());
    tex_palette_free(p);
}

/* OKLab to sRGB by the definition: Ottosson's matrices, the cube, and the sRGB encoding
 * through libm's pow, each channel rounded once to float. */
static double encode_by_pow(double c)
{
    if (c <= 0.0)
        return 0.0;
    if (c >= 1.0)
        return 1.0;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1 / 2.4) - 0.055;
}

static void oklab_by_definition(const float lab[3], float rgb[3])
{
    double l = lab[0] + 0.3963377774 * lab[1] + 0.2158037573 * lab[2];
    double m = lab[0] - 0.1055613458 * lab[1] - 0.0638541728 * lab[2];
    double s = lab[0] - 0.0894841775 * lab[1] - 1.2914855480 * lab[2];
    l = l * l * l, m = m * m * m, s = s * s * s;
    rgb[0] = (float)encode_by_pow(4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s);
    rgb[1] = (float)encode_by_pow(-1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s);
    rgb[2] = (float)encode_by_pow(-0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s);
}

/* tex_oklab_to_srgb's polynomial encoding gives pow's floats bit for bit, over colours in
 * and out of gamut (a million of them: some 250 encodings take the fallback to pow). */
static void test_oklab_encoding(void)
{
    long bad = 0, n = 1000000;
    uint64_t x = 0x9e3779b97f4a7c15u;
    for (long i = 0; i < n; i++) {
        float lab[3], a[3], b[3];
        for (int k = 0; k < 3; k++) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17; /* xorshift: no libtex in the oracle */
            double u = (x >> 11) * 0x1p-53;
            lab[k] = (float)(k ? 0.8 * u - 0.4 : 1.1 * u - 0.05);
        }
        tex_oklab_to_srgb(lab, a);
        oklab_by_definition(lab, b);
        bad += memcmp(a, b, sizeof a) != 0;
    }
    CHECKF(bad == 0, "OKLab to sRGB equals the definition through pow, bit for bit (%ld of %ld "
                     "differ)", bad, n);
}

/* The lookup hits every stop exactly (a hard edge gives the later colour). */
static void test_lookup(const tex_palette *p)
{
    float c[4], want[4];

    tex_palette_lookup(p, 0.0f, c);
    CHECK(same4(c, p->stops[0].rgba), "t = 0 is the first stop");
    tex_palette_lookup(p, 0.25f, c);
    CHECK(same4(c, p->stops[2].rgba), "t = 0.25 (hard edge) is the later stop");
    tex_palette_lookup(p, 0.8f, c);
    CHECK(same4(c, p->stops[3].rgba), "t = 0.8 is the last stop exactly");
    tex_palette_lookup(p, 1.0f, c);
    CHECK(same4(c, p->stops[3].rgba), "past the last stop: its colour");
    tex_palette_lookup(p, -3.0f, c);
    CHECK(same4(c, p->stops[0].rgba), "below 0 clamps");
    tex_palette_lookup(p, NAN, c);
    CHECK(same4(c, p->stops[0].rgba), "NaN gives the first colour");
    CHECKF(fabsf(p->stops[2].rgba[3] - 128 / 255.0f) < 1e-7f, "hex alpha (%g)", p->stops[2].rgba[3]);

    /* Indexed colours and the fallbacks. */
    tex_palette_index(p, 1, c);
    CHECK(c[0] == 0 && c[1] == 0 && c[2] == 1 && c[3] == 1, "index 1 (sorted after parsing)");
    tex_palette_index(p, 2, c);
    CHECK(c[0] == 0 && c[1] == 1 && c[2] == 0, "index 2");
    tex_palette_index_n(p, 3, 3, c);
    tex_palette_lookup(p, 1.0f, want);
    CHECK(same4(c, want), "id 3 of 3 without an entry takes the gradient's end");
}

/* RGB interpolation is linear; OKLab round-trips colours. */
static void test_interpolation(void)
{
    tex_palette *q = parse("0 0 0 0\n1 1 0.5 0.25 0.5\n");
    float c[4];

    tex_palette_lookup(q, 0.5f, c);
    CHECKF(fabsf(c[0] - 0.5f) < 1e-6f && fabsf(c[1] - 0.25f) < 1e-6f && fabsf(c[3] - 0.75f) < 1e-6f,
           "rgb midpoint (%g %g %g %g)", c[0], c[1], c[2], c[3]);
    tex_palette_free(q);
    {
        float rgb[3] = {0.8f, 0.3f, 0.1f}, lab[3], back[3], white[3] = {1, 1, 1};
        tex_srgb_to_oklab(rgb, lab);
        tex_oklab_to_srgb(lab, back);
        CHECKF(fabsf(back[0] - rgb[0]) < 1e-4f && fabsf(back[1] - rgb[1]) < 1e-4f &&
                   fabsf(back[2] - rgb[2]) < 1e-4f,
               "OKLab round trip (%g %g %g)", back[0], back[1], back[2]);
        tex_srgb_to_oklab(white, lab);
        CHECKF(fabsf(lab[0] - 1) < 1e-4f && fabsf(lab[1]) < 1e-4f && fabsf(lab[2]) < 1e-4f,
               "white is L=1 a=b=0 (%g %g %g)", lab[0], lab[1], lab[2]);
    }
    /* OKLab midpoint of black and white is perceptual mid-grey (L = 0.5), not 0.5 sRGB. */
    q = parse("space oklab\n0 #000000\n1 #ffffff\n");
    tex_palette_lookup(q, 0.5f, c);
    {
        float lab[3];
        tex_srgb_to_oklab(c, lab);
        CHECKF(fabsf(lab[0] - 0.5f) < 1e-3f && fabsf(c[0] - c[2]) < 1e-5f,
               "oklab midpoint has L = 0.5 (L=%g, rgb %g)", lab[0], c[0]);
    }
    tex_palette_free(q);
    test_oklab_encoding();
}

/* Round trip through the text format. */
static void test_round_trip(const tex_palette *p)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    int ok = fp && tex_palette_write(p, fp) == 0;
    if (fp)
        fclose(fp);
    tex_palette *q = ok ? tex_palette_parse(buf, len, "mem") : NULL;
    ok = q && q->nstops == p->nstops && q->nindex == p->nindex && q->space == p->space;
    for (int i = 0; ok && i < p->nstops; i++)
        ok = q->stops[i].pos == p->stops[i].pos && same4(q->stops[i].rgba, p->stops[i].rgba);
    for (int i = 0; ok && i < p->nindex; i++)
        ok = q->index[i].id == p->index[i].id && same4(q->index[i].rgba, p->index[i].rgba);
    CHECK(ok, "write then parse gives the same palette, bit for bit");
    tex_palette_free(q);
    free(buf);
}

/* Bad input: one message with file and line. */
static void test_errors(void)
{
    check_error("0 #000000\n0.5 #ffffff\n0.4 #808080\n", "t.pal:3: stops out of order",
                "unsorted stops");
    check_error("1.5 #000000\n", "t.pal:1: stop position must be in 0..1", "a position above 1");
    check_error("-0.1 #000000\n", "t.pal:1: stop position must be in 0..1", "a negative position");
    check_error("0 #12345\n", "t.pal:1: bad hex colour", "a 5-digit hex colour");
    check_error("0 #gg0000\n", "t.pal:1: bad hex colour", "a non-hex digit");
    check_error("0 0.5 1.2 0\n", "t.pal:1: green must be in 0..1", "a component above 1");
    check_error("# nothing\n\n", "t.pal:2: empty palette", "an empty palette");
    check_error("", "empty palette", "an empty file");
    check_error("0 0.5 0.5\n", "t.pal:1: a colour needs", "two components");
    check_error("spaces rgb\n", "t.pal:1: unknown keyword", "an unknown keyword");
    check_error("space hsv\n", "t.pal:1: want 'space rgb'", "an unknown space");
    check_error("index 1 #fff\nindex 1 #000\n", "t.pal:2: index 1 given twice", "a repeated index");
    check_error("index -1 #fff\n", "t.pal:1: index: region id", "a negative region id");
    check_error("0 nan 0 0\n", "t.pal:1: red: not a number", "NaN");
    check_error("0 #fff #000\n", "unexpected", "two colours");
}

/* Colouring maps: a region-id map takes indexed colours, a scalar map the gradient. */
static void test_maps(void)
{
    tex_palette *p = parse("0 #000000\n1 #ffffff80\nindex 2 #ff0000\n");
    tex_map *m = tex_map_new(3, 1, 1), *o;
    m->subregions = 3;
    m->px[0] = 1, m->px[1] = 2, m->px[2] = 3;
    o = tex_palette_map(p, m, NAN, NAN, TEX_OUTSIDE_CLAMP);
    CHECK(o && o->nc == 4 && o->px[0] == 0 && o->px[3] == 1 && o->px[4] == 1 && o->px[5] == 0 &&
              o->px[8] == 1 && o->px[11] == 128 / 255.0f,
          "region ids 1..3: gradient start, index 2, gradient end (RGBA: the palette has alpha)");
    tex_map_free(o);
    m->subregions = 0;
    o = tex_palette_map(p, m, 1, 3, TEX_OUTSIDE_CLAMP);
    CHECK(o && o->px[4] > 0.49f && o->px[4] < 0.51f, "scalar map: the middle of the range");
    tex_map_free(o);
    CHECK(tex_palette_t(1.25, 0, 1, TEX_OUTSIDE_REPEAT) == 0.25f &&
              tex_palette_t(1.25, 0, 1, TEX_OUTSIDE_MIRROR) == 0.75f &&
              tex_palette_t(-0.25, 0, 1, TEX_OUTSIDE_MIRROR) == 0.25f &&
              tex_palette_t(1.25, 0, 1, TEX_OUTSIDE_CLAMP) == 1.0f &&
              tex_palette_t(1.0, 0, 1, TEX_OUTSIDE_REPEAT) == 1.0f,
          "outside modes: repeat, mirror, clamp (and 1 stays 1)");
    tex_map_free(m);
    m = tex_map_new(2, 2, 3);
    o = tex_palette_map(p, m, 0, 1, TEX_OUTSIDE_CLAMP);
    CHECK(!o && strstr(tex_errmsg(), "3 channels"), "an RGB map is refused");
    tex_map_free(m);
    tex_palette_free(p);
}

/* A map coloured in runs (sixteen values at a time where the CPU has AVX-512, their OKLab
 * colours taken to sRGB eight at a time) has tex_palette_lookup's bytes at every pixel, at
 * every SIMD level: dark colours on the linear toe, colours out of gamut that clamp to 0 and
 * 1, NaN, values outside the range in each --outside mode, values at a stop, stops at one
 * place, alpha, 1, 2, 8, 9 and 16 stops and more than the kernels' lanes, an odd count. */
static void test_map_runs(void)
{
    static const char *const pals[] = {
        "space oklab\n0 #000000\n0.3 #030303\n0.5 #0000ff\n0.7 #ffff00\n1 #ff00ff\n",
        "space rgb\n0 #ff000080\n0.25 #00ff00\n0.25 #0000ff\n0.5 1 1 0 0.5\n1 #ffffff40\n",
        "space oklab\n0 #ff000080\n0.5 #00ff00\n0.5 #102030\n1 #ffffff40\n",
        "space rgb\n0.2 #336699\n0.6 #996633\n",
        "space oklab\n0 #000000\n0.05 #100000\n0.1 #200000\n0.15 #300000\n0.2 #400000\n"
        "0.25 #500000\n0.3 #600000\n0.35 #700000\n0.4 #800000\n0.45 #900000\n0.5 #a00000\n"
        "0.55 #b00000\n0.6 #c00000\n0.65 #d00000\n0.7 #e00000\n0.75 #f00000\n0.8 #ff0000\n"
        "1 #ffffff\n",
        /* one stop, and 8, 9, 16: the AVX2 kernel's lanes, one permute or two */
        "space oklab\n0.4 #336699c0\n",
        "space rgb\n0 #000000\n0.1 #ff0000\n0.2 #00ff00c0\n0.35 #0000ff\n0.5 #ffff00\n"
        "0.6 #00ffff\n0.8 #ff00ff80\n1 #ffffff\n",
        "space oklab\n0 #000000\n0.1 #ff0000\n0.2 #00ff00\n0.35 #0000ff\n0.5 #ffff00\n"
        "0.6 #00ffff\n0.8 #ff00ff\n0.9 #808080\n1 #ffffff\n",
        "space oklab\n0 #000000\n0.05 #200000\n0.1 #002000\n0.2 #000020\n0.25 #404000\n"
        "0.3 #004040\n0.4 #400040\n0.45 #808000\n0.5 #008080c0\n0.55 #800080\n0.6 #c0c000\n"
        "0.7 #00c0c0\n0.75 #c000c0\n0.8 #ff8000\n0.9 #0080ff\n1 #ffffff\n"};
    static const double range[][2] = {{0, 1}, {-0.3, 0.2}, {0.5, 0.5}};
    enum { N = 4099 };
    tex_map *m = tex_map_new(N, 1, 1);
    uint64_t x = 1;
    int cases = 0, bad = 0, toe = 0, zeros = 0, ones = 0, best = tex_simd_level();
    for (int i = 0; m && i < N; i++) {
        x = x * 6364136223846793005ULL + 1442695040888963407ULL;
        m->px[i] = i % 3 ? -0.1f + 1.2f * i / (N - 1) : (float)(x >> 40) / (1 << 24);
        if (i % 97 == 0)
            m->px[i] = (float)(i % 5) * 0.25f; /* at the stops */
    }
    if (m)
        m->px[7] = NAN, m->px[8] = INFINITY, m->px[9] = -1e30f;
    for (size_t q = 0; m && q < sizeof pals / sizeof *pals; q++) {
        tex_palette *p = parse(pals[q]);
        for (size_t r = 0; p && r < sizeof range / sizeof *range; r++)
            for (int out = TEX_OUTSIDE_CLAMP; out <= TEX_OUTSIDE_MIRROR; out++)
                for (int level = best; level >= TEX_SIMD_SCALAR; level--, cases++) {
                    double lo = range[r][0], hi = range[r][1];
                    tex_simd_limit(level);
                    tex_map *o = tex_palette_map(p, m, lo, hi, out);
                    int same = o != NULL;
                    for (int i = 0; o && i < N; i++) {
                        float c[4];
                        tex_palette_lookup(p, tex_palette_t(m->px[i], lo, hi, out), c);
                        same &= !memcmp(c, o->px + o->nc * i, (size_t)o->nc * sizeof *c);
                        for (int k = 0; q == 0 && k < 3; k++) {
                            zeros += c[k] == 0 && i > N / 2, ones += c[k] == 1 && i > N / 2;
                            toe += c[k] > 0 && c[k] < 0.04f;
                        }
                    }
                    bad += !same;
                    tex_map_free(o);
                }
        tex_palette_free(p);
    }
    tex_simd_limit(TEX_SIMD_AVX512);
    CHECKF(cases == 9 * 3 * 3 * (best + 1) && !bad && zeros && ones && toe,
           "%d colourings of %d values (9 palettes, 3 ranges, 3 outside modes, each SIMD level) "
           "are lookup's bytes: %d differ (%d clamped to 0 and %d to 1 out of gamut, %d on the toe)",
           cases, N, bad, zeros, ones, toe);
    tex_map_free(m);
}

/* Only index lines: they double as the gradient. */
static void test_indexed_only(void)
{
    tex_palette *p = parse("index 1 #000000\nindex 2 #ffffff\n");
    float c[4];

    tex_palette_lookup(p, 1.0f, c);
    CHECK(p && c[0] == 1.0f, "an indexed-only palette has a gradient");
    tex_palette_free(p);
}

/* Every shipped palette loads by name from the source tree. */
static void test_shipped(void)
{
    static const char *const names[] = {"wood", "marble", "granite", "fire", "clouds",
                                        "sky", "earth", "water", "brick", "grass", "greys",
                                        "rainbow", "viridis", "magma", "inferno", "plasma"};
    char dir[4096];
    unit_top_path("palettes", dir, sizeof dir);
    setenv("TEXTURA_PALETTES", dir, 1);
    tex_palette *p;
    float c[4];
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        p = tex_palette_load(names[i]);
        CHECKF(p && p->nstops >= 2, "palette %s loads (%s)", names[i], p ? "" : tex_errmsg());
        tex_palette_free(p);
    }
    p = tex_palette_load("viridis");
    tex_palette_lookup(p, 0.0f, c);
    CHECK(p && c[0] == 0.267004f && c[2] == 0.329415f, "viridis starts at its published value");
    tex_palette_free(p);
    p = tex_palette_load("no-such-palette");
    CHECK(!p && tex_errkind() == TEX_ERR_USAGE && strstr(tex_errmsg(), "no-such-palette"),
          "an unknown name is a usage error naming it");
    p = tex_palette_load("../x/missing.pal");
    CHECK(!p && strstr(tex_errmsg(), "missing.pal"), "a missing file is an error naming it");
}

int main(void)
{
    static const char *const text = "# test\n"
                                    "space oklab\n"
                                    "0    #102030\n"
                                    "0.25 0.5 0.25 0.125 # trailing comment\n"
                                    "0.25 #ff000080\n"
                                    "0.8  0.9 0.8 0.7 0.5\n"
                                    "index 2 #00ff00\n"
                                    "index 1 0 0 1\n";
    tex_palette *p = parse(text);

    CHECKF(p != NULL, "a palette parses (%s)", p ? "" : tex_errmsg());
    if (!p)
        return unit_done();
    CHECK(p->nstops == 4 && p->nindex == 2 && p->space == TEX_SPACE_OKLAB, "stops, index, space");
    test_lookup(p);
    test_round_trip(p);
    tex_palette_free(p);
    test_interpolation();
    test_errors();
    test_maps();
    test_map_runs();
    test_indexed_only();
    test_shipped();
    return unit_done();
}
