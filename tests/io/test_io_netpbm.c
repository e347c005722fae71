/* test_io_netpbm.c - PBM, PGM, PPM (plain and raw), PAM and PFM read and written without a
 * library: samples v of maxval M read as v/M, written back to the nearest level */
#define _GNU_SOURCE
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "textura.h"
#include "unit.h"

/* The file image decodes to a w x h x nc map of the samples want, exactly. */
static void decodes_to(const void *data, size_t len, int w, int h, int nc, const float *want,
                       const char *what)
{
    tex_map *m = tex_netpbm_decode(data, len, "in.pnm");
    int same = m && m->w == w && m->h == h && m->nc == nc;

    if (!m)
        printf("# %s\n", tex_errmsg());
    for (int i = 0; same && i < w * h * nc; i++)
        if (m->px[i] != want[i]) {
            printf("# sample %d: %.9g, not %.9g\n", i, m->px[i], want[i]);
            same = 0;
        }
    CHECK(same, what);
    tex_map_free(m);
}

static void test_plain(void)
{
    static const char p1[] = "P1\n# a comment\n3 2\n1 0 1\n0 1 0\n";
    static const char p2[] = "P2 3 1 4 0 2 4";
    static const char p3[] = "P3\n2 1\n255\n255 0 0  0 128 255\n";
    const float f1[] = {0, 1, 0, 1, 0, 1}, f2[] = {0, 0.5f, 1};
    const float f3[] = {1, 0, 0, 0, (float)(128 / 255.0), 1};

    decodes_to(p1, sizeof p1 - 1, 3, 2, 1, f1, "P1: 1 is black (0.0), 0 white (1.0)");
    decodes_to(p2, sizeof p2 - 1, 3, 1, 1, f2, "P2: v of maxval 4 reads v/4");
    decodes_to(p3, sizeof p3 - 1, 2, 1, 3, f3, "P3: RGB triples, v/255 the nearest float");
}

static void test_raw(void)
{
    static const unsigned char p4[] = "P4\n10 2\n\xA5\xC0\x00\x40";
    static const unsigned char p5[] = "P5 4 1 65535\n\x00\x00\x00\x01\xff\xff\x80\x00";
    static const unsigned char p6[] = "P6 1 1 255\n\x10\x80\xff";
    static const unsigned char p7[] = "P7\nWIDTH 2\nHEIGHT 1\nDEPTH 4\nMAXVAL 255\n"
                                      "TUPLTYPE RGB_ALPHA\nENDHDR\n"
                                      "\x00\x33\x66\x99\xcc\xff\x01\x02";
    float f4[20], f5[4], f6[3], f7[8];
    const unsigned char bits[] = {0xA5, 0xC0, 0x00, 0x40};

    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 10; x++)
            f4[y * 10 + x] = bits[y * 2 + x / 8] >> (7 - x % 8) & 1 ? 0.0f : 1.0f;
    f5[0] = 0, f5[1] = (float)(1 / 65535.0), f5[2] = 1, f5[3] = (float)(32768 / 65535.0);
    f6[0] = (float)(16 / 255.0), f6[1] = (float)(128 / 255.0), f6[2] = 1;
    for (int i = 0; i < 8; i++)
        f7[i] = (float)(p7[sizeof p7 - 9 + i] / 255.0);
    decodes_to(p4, sizeof p4 - 1, 10, 2, 1, f4, "P4: rows of bits padded to whole bytes");
    decodes_to(p5, sizeof p5 - 1, 4, 1, 1, f5, "P5 of maxval 65535: big-endian 16-bit samples");
    decodes_to(p6, sizeof p6 - 1, 1, 1, 3, f6, "P6: one RGB pixel");
    decodes_to(p7, sizeof p7 - 1, 2, 1, 4, f7, "P7: RGB_ALPHA as stored, not premultiplied");
}

static void test_pfm(void)
{
    /* rows bottom to top; a negative scale: little-endian */
    unsigned char le[64] = "Pf\n2 2\n-1.0\n", be[64] = "PF\n1 1\n1.0\n";
    const float grey[4] = {0.25f, -3.5f, 1e30f, 0}, want[4] = {1e30f, 0, 0.25f, -3.5f};
    const float rgb[3] = {0.5f, 2, -1};
    size_t nle = strlen((char *)le), nbe = strlen((char *)be);

    memcpy(le + nle, grey, sizeof grey); /* this test runs on a little-endian machine */
    for (int i = 0; i < 3; i++) {
        unsigned char *b = (unsigned char *)&rgb[i];
        for (int k = 0; k < 4; k++)
            be[nbe + 4 * i + k] = b[3 - k];
    }
    decodes_to(le, nle + sizeof grey, 2, 2, 1, want, "Pf: little-endian, the last row first");
    decodes_to(be, nbe + sizeof rgb, 1, 1, 3, rgb, "PF: big-endian RGB");
}

static void test_refused(void)
{
    static const char over[] = "P2 2 1 100 50 101";
    static const unsigned char cut[] = "P5 4 4 255\n\x01\x02\x03";
    tex_map *m = tex_netpbm_decode(over, sizeof over - 1, "over.pgm");
    CHECKF(!m && strstr(tex_errmsg(), "over.pgm"), "a sample above maxval is refused, "
           "naming the file (%s)", tex_errmsg());
    tex_map_free(m);
    m = tex_netpbm_decode(cut, sizeof cut - 1, "cut.pgm");
    CHECKF(!m && strstr(tex_errmsg(), "cut.pgm"), "a raw file cut short is refused, naming "
           "it (%s)", tex_errmsg());
    tex_map_free(m);
}

/* Written, then read back: each sample the nearest of the depth's levels. */
static void test_write(void)
{
    static const struct {
        int nc, depth;
        enum tex_pnm_variant v;
        const char *magic;
    } cases[] = {{1, 8, TEX_PNM_AUTO, "P5"}, {3, 16, TEX_PNM_AUTO, "P6"},
                 {4, 16, TEX_PNM_PAM, "P7"}, {1, 8, TEX_PNM_PBM, "P4"}};
    char path[] = "/tmp/test_io_netpbm.XXXXXX";
    int fd = mkstemp(path);

    for (size_t k = 0; fd >= 0 && k < sizeof cases / sizeof *cases; k++) {
        tex_map *m = tex_map_new(9, 5, cases[k].nc), *r = NULL;
        double levels = cases[k].depth == 8 ? 255 : 65535;
        char head[3] = "";
        int near = 1;
        for (size_t i = 0; i < tex_map_samples(m); i++)
            m->px[i] = (float)((i * 7919u) % 1000) / 999.0f * 1.2f - 0.1f; /* clamped */
        if (ftruncate(fd, 0) == 0 && lseek(fd, 0, SEEK_SET) == 0 &&
            tex_pnm_write_fd(m, fd, cases[k].depth, cases[k].v, path) == 0 &&
            pread(fd, head, 2, 0) == 2)
            r = tex_map_read(path);
        for (size_t i = 0; r && i < tex_map_samples(m); i++) {
            double v = m->px[i] < 0 ? 0 : m->px[i] > 1 ? 1 : m->px[i];
            double want = cases[k].v == TEX_PNM_PBM ? (v < 0.5 ? 0 : 1)
                                                     : floor(v * levels + 0.5) / levels;
            near &= r->px[i] == (float)want;
        }
        CHECKF(r && !strcmp(head, cases[k].magic) && r->nc == cases[k].nc && near,
               "%s, %d channel(s), depth %d: written and read back to the nearest level",
               cases[k].magic, cases[k].nc, cases[k].depth);
        tex_map_free(m);
        tex_map_free(r);
    }
    if (fd >= 0) {
        tex_map *m = tex_map_new(6, 4, 3), *r = NULL;
        for (size_t i = 0; i < tex_map_samples(m); i++)
            m->px[i] = (float)i * -1.5e-3f + 7;
        if (ftruncate(fd, 0) == 0 && lseek(fd, 0, SEEK_SET) == 0 &&
            tex_pfm_write_fd(m, fd, path) == 0)
            r = tex_map_read(path);
        CHECK(r && r->nc == 3 && !memcmp(r->px, m->px, tex_map_samples(m) * 4),
              "PFM: written and read back bit for bit");
        tex_map_free(m);
        tex_map_free(r);
        close(fd);
        unlink(path);
    }
}

int main(void)
{
    test_plain();
    test_raw();
    test_pfm();
    test_refused();
    test_write();
    return unit_done();
}
