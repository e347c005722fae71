/* file.c - texture maps from and to files, pipes and other formats */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/error.h"
#include "base/paths.h"
#include "io/codec_bridge.h"
#include "io/file.h"
#include "io/limit.h"
#include "io/netpbm.h"
#include "io/prosim.h"
#include "io/oiio_bridge.h"

static const struct {
    enum tex_format f;
    const char *name; /* also the extension handed to OpenImageIO */
    const char *exts; /* every extension that names the format */
    int float_ok;     /* can hold float32 */
    int max_int_depth;
    unsigned nc_ok;   /* bit k-1 set: the writer takes k channels (measured on OIIO 2.4) */
} formats[] = {
    {TEX_FMT_UNKNOWN, "unknown", "", 0, 0, 0},
    {TEX_FMT_EXR, "exr", " exr ", 1, 0, 15},
    {TEX_FMT_PNG, "png", " png ", 0, 16, 13}, /* 2 channels: RGB, B = 0, not grey+alpha */
    {TEX_FMT_TIFF, "tif", " tif tiff ", 1, 16, 15},
    {TEX_FMT_PNM, "pnm", " pnm ", 0, 16, 5},
    {TEX_FMT_PFM, "pfm", " pfm ", 1, 0, 5},
    {TEX_FMT_BMP, "bmp", " bmp ", 0, 8, 13},
    {TEX_FMT_TGA, "tga", " tga ", 0, 8, 15},
    {TEX_FMT_HDR, "hdr", " hdr rgbe ", 1, 0, 4},
    {TEX_FMT_JPEG, "jpg", " jpg jpeg ", 0, 8, 5},
    {TEX_FMT_GIF, "gif", " gif ", 0, 8, 12},
    {TEX_FMT_WEBP, "webp", " webp ", 0, 8, 12},
    {TEX_FMT_DPX, "dpx", " dpx ", 0, 16, 13},
    {TEX_FMT_PAM, "pam", " pam ", 0, 16, 13},
    {TEX_FMT_PBM, "pbm", " pbm ", 0, 8, 5},
    {TEX_FMT_PPM, "ppm", " ppm ", 0, 16, 4},
    {TEX_FMT_PGM, "pgm", " pgm ", 0, 16, 1},
    {TEX_FMT_PROSIM, "r", " r g b ", 0, 8, 4}, /* ProSim's three files (prosim.h) */
    {TEX_FMT_PIC, "pic", " pic ", 1, 0, 1},
};

const char *tex_format_name(enum tex_format f)
{
    return formats[f].name;
}

const char *tex_format_exts(enum tex_format f)
{
    return formats[f].exts;
}

/* The format an extension word names (ext[0..n)), TEX_FMT_UNKNOWN if none. */
static enum tex_format format_of_word(const char *ext, size_t n)
{
    char w[16];

    if (n == 0 || n > 5)
        return TEX_FMT_UNKNOWN;
    snprintf(w, sizeof w, " %.*s ", (int)n, ext);
    for (char *p = w; *p; p++)
        *p = (char)(*p >= 'A' && *p <= 'Z' ? *p + 32 : *p);
    for (size_t i = 1; i < sizeof formats / sizeof *formats; i++)
        if (strstr(formats[i].exts, w))
            return formats[i].f;
    return TEX_FMT_UNKNOWN;
}

enum tex_format tex_format_from_name(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');

    if (!dot || (slash && dot < slash))
        return TEX_FMT_UNKNOWN;
    return format_of_word(dot + 1, strlen(dot + 1));
}

/* The formats netpbm.c writes (PFM aside). */
static int is_netpbm(enum tex_format f)
{
    return f == TEX_FMT_PNM || f == TEX_FMT_PPM || f == TEX_FMT_PGM || f == TEX_FMT_PAM ||
           f == TEX_FMT_PBM;
}

#define FORMAT_LIST                                                                          \
    "exr, png, tif, pnm, ppm, pgm, pam, pbm, pfm, bmp, tga, hdr, jpg, webp, dpx, r (ProSim's " \
    ".r/.g/.b), pic"

/* Standard output by another name: /dev/stdout, /dev/fd/1, /proc/self/fd/1. */
static int names_stdout(const char *name)
{
    return !strcmp(name, "/dev/stdout") || !strcmp(name, "/dev/fd/1") ||
           !strcmp(name, "/proc/self/fd/1");
}

enum tex_format tex_output_format(const char *name, const char *format, const char **file)
{
    const char *colon = name ? strchr(name, ':') : NULL;
    enum tex_format f = TEX_FMT_UNKNOWN, g = TEX_FMT_UNKNOWN;
    struct stat st;

    if (format && (g = format_of_word(format, strlen(format))) == TEX_FMT_UNKNOWN) {
        tex_usage_error("--format %s: unknown format (" FORMAT_LIST ")", format);
        return TEX_FMT_UNKNOWN;
    }
    if (colon && (f = format_of_word(name, (size_t)(colon - name))) != TEX_FMT_UNKNOWN) {
        if (format && g != f) {
            tex_usage_error("--format %s contradicts %s", format, name);
            return TEX_FMT_UNKNOWN;
        }
        name = colon + 1;
    }
    *file = !name || !strcmp(name, "-") || names_stdout(name) ? NULL : name;
    if (f != TEX_FMT_UNKNOWN)
        return f;
    if (g != TEX_FMT_UNKNOWN) {
        if (*file && (f = tex_format_from_name(*file)) != TEX_FMT_UNKNOWN && f != g) {
            tex_usage_error("--format %s contradicts the extension of %s (prefix it: %s:%s)",
                            format, *file, format, *file);
            return TEX_FMT_UNKNOWN;
        }
        return g;
    }
    if (!*file)
        return TEX_FMT_EXR;
    if ((f = tex_format_from_name(*file)) != TEX_FMT_UNKNOWN)
        return f;
    if (stat(*file, &st) == 0 && S_ISDIR(st.st_mode)) {
        tex_error("%s: is a directory", *file);
        return TEX_FMT_UNKNOWN;
    }
    if (!strncmp(*file, "/dev/fd/", 8) || (stat(*file, &st) == 0 && !S_ISREG(st.st_mode)))
        return TEX_FMT_EXR; /* a stream, as standard output */
    tex_usage_error("%s: cannot tell the format from the extension (give it one of " FORMAT_LIST
                    ", a prefix such as png:%s, or --format)",
                    *file, *file);
    return TEX_FMT_UNKNOWN;
}

static int is_space(unsigned char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

enum tex_format tex_format_sniff(const void *head, size_t n)
{
    const unsigned char *b = head;

    if (n >= 4 && b[0] == 0x76 && b[1] == 0x2f && b[2] == 0x31 && b[3] == 0x01)
        return TEX_FMT_EXR;
    if (n >= 8 && memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0)
        return TEX_FMT_PNG;
    if (n >= 4 && (memcmp(b, "II*\0", 4) == 0 || memcmp(b, "MM\0*", 4) == 0 ||
                   memcmp(b, "II+\0", 4) == 0 || memcmp(b, "MM\0+", 4) == 0))
        return TEX_FMT_TIFF;
    if (n >= 3 && b[0] == 'P' && (b[1] == 'F' || b[1] == 'f') && is_space(b[2]))
        return TEX_FMT_PFM;
    if (n >= 3 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7' && is_space(b[2]))
        return b[1] == '7' ? TEX_FMT_PAM : b[1] == '1' || b[1] == '4' ? TEX_FMT_PBM : TEX_FMT_PNM;
    if (n >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff)
        return TEX_FMT_JPEG;
    if (n >= 6 && (memcmp(b, "GIF87a", 6) == 0 || memcmp(b, "GIF89a", 6) == 0))
        return TEX_FMT_GIF;
    if (n >= 12 && memcmp(b, "RIFF", 4) == 0 && memcmp(b + 8, "WEBP", 4) == 0)
        return TEX_FMT_WEBP;
    if (n >= 4 && (memcmp(b, "SDPX", 4) == 0 || memcmp(b, "XPDS", 4) == 0))
        return TEX_FMT_DPX;
    if (n >= 6 && (memcmp(b, "#?RADIANCE", n < 10 ? n : 10) == 0 || memcmp(b, "#?RGBE", 6) == 0))
        return TEX_FMT_HDR;
    if (n >= 26 && b[0] == 'B' && b[1] == 'M')
        return TEX_FMT_BMP;
    /* TGA has no magic number: accept a plausible header. */
    if (n >= 18 && b[1] <= 1 &&
        (b[2] == 1 || b[2] == 2 || b[2] == 3 || b[2] == 9 || b[2] == 10 || b[2] == 11) &&
        (b[16] == 8 || b[16] == 15 || b[16] == 16 || b[16] == 24 || b[16] == 32) &&
        (b[12] | b[13]) && (b[14] | b[15]) && (b[1] == 1 || (b[3] | b[4] | b[5] | b[6] | b[7]) == 0))
        return TEX_FMT_TGA;
    return TEX_FMT_UNKNOWN;
}

/* ---- the bridges, each loaded on first use ---- */

/* A shared object in LIBDIR/textura exporting one versioned struct. */
struct bridge_slot {
    const char *file, *symbol, *what, *env;
    int version;
    const void *b;
    char msg[PATH_MAX + 128]; /* why loading failed, kept for later calls */
};

static struct bridge_slot oiio_slot = {"textura-oiio.so", "tex_oiio_bridge", "OpenImageIO",
                                       "TEXTURA_OIIO_BRIDGE", TEX_OIIO_BRIDGE_VERSION, NULL, ""};
static struct bridge_slot png_slot = {"textura-png.so", "tex_png_bridge", "PNG", NULL,
                                      TEX_CODEC_BRIDGE_VERSION, NULL, ""};
static struct bridge_slot jpeg_slot = {"textura-jpeg.so", "tex_jpeg_bridge", "JPEG", NULL,
                                       TEX_CODEC_BRIDGE_VERSION, NULL, ""};
static struct bridge_slot tiff_slot = {"textura-tiff.so", "tex_tiff_bridge", "TIFF", NULL,
                                       TEX_CODEC_BRIDGE_VERSION, NULL, ""};

/* The bridge's struct (which starts with its version), or NULL with the error set.
 * It is found at $env when set, else in the install's LIBDIR/textura (paths.h). */
static const void *bridge_load(struct bridge_slot *s)
{
    const char *env = s->env ? getenv(s->env) : NULL;
    char path[PATH_MAX];
    void *h;

    if (s->b)
        return s->b;
    if (s->msg[0]) {
        tex_error("%s", s->msg);
        return NULL;
    }
    if (env && *env)
        snprintf(path, sizeof path, "%s", env);
    else
        snprintf(path, sizeof path, "%s/textura/%s", tex_install_dir(TEX_DIR_LIB), s->file);
    if ((h = dlopen(path, RTLD_NOW | RTLD_LOCAL)) && (s->b = dlsym(h, s->symbol)) &&
        *(const int *)s->b == s->version)
        return s->b;
    s->b = NULL;
    {
        const char *why = dlerror();
        snprintf(s->msg, sizeof s->msg, "cannot load the %s bridge %s: %s", s->what, path,
                 why ? why : "wrong version");
    }
    tex_error("%s", s->msg);
    return NULL;
}

static const struct tex_oiio_bridge *bridge(void)
{
    return bridge_load(&oiio_slot);
}

static struct bridge_slot *codec_slot(enum tex_format f)
{
    return f == TEX_FMT_PNG ? &png_slot : f == TEX_FMT_JPEG ? &jpeg_slot
                                        : f == TEX_FMT_TIFF ? &tiff_slot : NULL;
}

/* Files with more channels than a map holds keep the first four. */
static int keep_channels(int nc, const char *name)
{
    if (nc > TEX_MAP_MAX_CHANNELS) {
        tex_warning("%s: %d channels, the first %d kept", name, nc, TEX_MAP_MAX_CHANNELS);
        return TEX_MAP_MAX_CHANNELS;
    }
    return nc;
}

/* ---- reading ---- */

/* buffers from this size up (a file read whole, samples quantised) take fresh pages */
#define PAGES_FROM (1 << 20)

/* Read fd to its end, refusing more than max bytes (SIZE_MAX: no limit).  pages: an empty
 * b takes a large file's size in fresh pages (tex_pages_new), as maps do: read into the
 * heap, a large map's first touch of 4 KiB pages cost more than reading it
 * (doc/performance.md, io/ and cli/). */
static int read_fd_max(int fd, tex_buf *b, const char *name, size_t max, int pages)
{
    struct stat st;
    size_t want = 1 << 20;

    if (fstat(fd, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return tex_error("%s: is a directory", name);
        if (S_ISREG(st.st_mode) && st.st_size > 0)
            want = (size_t)st.st_size + 1;
    }
    if (pages && !b->cap && want >= PAGES_FROM) {
        if (!(b->data = tex_pages_new(want, PAGES_FROM, &b->mapped)))
            return tex_error("%s: out of memory (%zu bytes)", name, want);
        b->cap = want;
    }
    for (;;) {
        ssize_t r;
        /* pages hold the file's size and a byte more, where its end is read */
        if (b->cap - b->len < (b->mapped ? 1 : 1 << 16) &&
            tex_buf_reserve(b, b->len + (b->len > want ? b->len : want)) < 0)
            return -1;
        r = read(fd, b->data + b->len, b->cap - b->len);
        if (r == 0)
            return 0;
        if (r < 0) {
            if (errno == EINTR)
                continue;
            return tex_error("%s: %s", name, strerror(errno));
        }
        b->len += (size_t)r;
        if (b->len > max)
            return tex_error("%s: larger than %zu bytes", name, max);
    }
}

int tex_read_fd(int fd, tex_buf *b, const char *name)
{
    size_t max;
    if (tex_input_max(&max) < 0)
        return -1;
    if (read_fd_max(fd, b, name, max, 1) < 0)
        return b->len > max ? tex_error("%s: over the input limit of %zu bytes (TEXTURA_MAX_INPUT)",
                                        name, max)
                            : -1;
    return 0;
}

char *tex_read_text(const char *path, size_t max, size_t *len, const char *what)
{
    int from_stdin = !strcmp(path, "-");
    const char *name = from_stdin ? "standard input" : path;
    int fd = from_stdin ? 0 : open(path, O_RDONLY | O_CLOEXEC);
    tex_buf b = {0};
    int r;

    if (fd < 0) {
        tex_error("%s: %s", name, strerror(errno));
        return NULL;
    }
    r = read_fd_max(fd, &b, name, max, 0);
    if (!from_stdin)
        close(fd);
    if (r == 0 && tex_buf_reserve(&b, b.len + 1) == 0) {
        b.data[b.len] = '\0';
        *len = b.len;
        return (char *)b.data;
    }
    if (b.len > max)
        tex_error("%s: larger than %zu bytes for %s", name, max, what);
    tex_buf_free(&b);
    return NULL;
}

static tex_map *read_bridged(const char *path, const void *mem, size_t len, enum tex_format f,
                             const char *name)
{
    const struct tex_oiio_bridge *br = bridge();
    struct tex_oiio_in *in;
    char err[400] = "";
    int w, h, nc;
    tex_map *m = NULL;

    if (!br) {
        tex_error_context(name);
        return NULL;
    }
    if (!(in = br->open(path, mem, len, tex_format_name(f), &w, &h, &nc, err, sizeof err))) {
        tex_error("%s: %s", name, err);
        return NULL;
    }
    nc = keep_channels(nc, name);
    if (tex_map_check_size(w, h, nc) < 0 || tex_input_check_decoded(w, h, nc) < 0 ||
        !(m = tex_map_new(w, h, nc))) {
        tex_error_context(name);
    } else if (br->read(in, m->px, nc, err, sizeof err) < 0) {
        tex_error("%s: %s", name, err);
        tex_map_free(m);
        m = NULL;
    }
    br->close(in);
    return m;
}

/* PNG, JPEG or TIFF through its codec bridge; OpenImageIO takes what it declines. */
static tex_map *read_codec(const char *path, const void *data, size_t len, enum tex_format f,
                           const char *name)
{
    const struct tex_codec_bridge *br = bridge_load(codec_slot(f));
    char err[400] = "";
    int w, h, nc, r;
    tex_map *m;

    if (!br) {
        tex_error_context(name);
        return NULL;
    }
    if ((r = br->info(data, len, &w, &h, &nc, err, sizeof err)) == TEX_CODEC_DECLINED)
        return path ? read_bridged(path, NULL, 0, f, name) : read_bridged(NULL, data, len, f, name);
    if (r < 0) {
        tex_error("%s: %s", name, err);
        return NULL;
    }
    nc = keep_channels(nc, name);
    if (tex_map_check_size(w, h, nc) < 0 || tex_input_check_decoded(w, h, nc) < 0 ||
        !(m = tex_map_new(w, h, nc))) {
        tex_error_context(name);
        return NULL;
    }
    if (br->read(data, len, m->px, err, sizeof err) < 0) {
        tex_error("%s: %s", name, err);
        tex_map_free(m);
        return NULL;
    }
    return m;
}

static tex_map *decode(const char *path, const void *data, size_t len, const char *name)
{
    enum tex_format f;
    tex_map *m;

    if (len == 0) {
        tex_error("%s: empty input, expected an image", name);
        return NULL;
    }
    f = tex_format_sniff(data, len);
    if (f == TEX_FMT_UNKNOWN && path)
        f = tex_format_from_name(path);
    if (f == TEX_FMT_UNKNOWN) {
        tex_error("%s: unknown image format (not EXR, PNG, TIFF, PNM, PFM, BMP, TGA, HDR, JPEG, "
                  "GIF, WebP or DPX)",
                  name);
        return NULL;
    }
    if (f == TEX_FMT_EXR) {
        /* DWAA/DWAB: OpenImageIO's OpenEXR decodes what the core cannot. */
        if (tex_exr_unsupported(data, len) && (m = read_bridged(NULL, data, len, f, name)))
            return m;
        if (!(m = tex_exr_decode(data, len, name)))
            tex_error_context(name);
        return m;
    }
    if (is_netpbm(f) || f == TEX_FMT_PFM)
        return tex_netpbm_decode(data, len, name);
    if (f == TEX_FMT_PROSIM || f == TEX_FMT_PIC) /* one file of the three: one channel */
        return tex_prosim_decode(data, len, f == TEX_FMT_PIC, path);
    if (codec_slot(f))
        return read_codec(path, data, len, f, name);
    /* A named file is opened by OpenImageIO itself (some formats can't read from memory). */
    return path ? read_bridged(path, NULL, 0, f, name) : read_bridged(NULL, data, len, f, name);
}

static enum tex_nonfinite nonfinite_policy = TEX_NONFINITE_REFUSE;
static float nonfinite_value;

void tex_map_set_nonfinite(enum tex_nonfinite policy, float value)
{
    nonfinite_policy = policy;
    nonfinite_value = value;
}

/* Whether any of n samples is NaN or infinite (its exponent all ones), in a loop the compiler
 * makes vector code of: the test of each sample with isfinite was 7 % of a blur's CPU in a
 * pipe (doc/performance.md) */
static int any_nonfinite(const float *px, size_t n)
{
    unsigned bad = 0;
#pragma omp simd reduction(| : bad)
    for (size_t i = 0; i < n; i++) {
        uint32_t b;
        memcpy(&b, px + i, sizeof b);
        bad |= (b & 0x7f800000u) == 0x7f800000u;
    }
    return bad != 0;
}

/* The map read, after the non-finite policy: m, or NULL (m freed) when refused. */
int tex_rows_nonfinite(float *px, int w, int n, int nc, int y0, const char *name)
{
    enum { BLOCK = 4096 };
    size_t total = (size_t)w * n * nc;

    if (nonfinite_policy == TEX_NONFINITE_KEEP)
        return 0;
    for (size_t b = 0; b < total; b += BLOCK) {
        size_t end = total - b < BLOCK ? total : b + BLOCK;
        if (!any_nonfinite(px + b, end - b))
            continue;
        for (size_t i = b; i < end; i++) {
            if (isfinite(px[i]))
                continue;
            if (nonfinite_policy == TEX_NONFINITE_REPLACE) {
                px[i] = nonfinite_value;
                continue;
            }
            return tex_error("%s: pixel (%zu,%zu) channel %zu is %s, not a finite number "
                             "(--nonfinite keep or --nonfinite VALUE to take it)",
                             name, i / nc % w, y0 + i / nc / w, i % nc,
                             isnan(px[i]) ? "NaN" : px[i] > 0 ? "+inf" : "-inf");
        }
    }
    return 0;
}

static tex_map *nonfinite(tex_map *m, const char *name)
{
    if (m && tex_rows_nonfinite(m->px, m->w, m->h, m->nc, 0, name) < 0) {
        tex_map_free(m);
        return NULL;
    }
    return m;
}

static tex_map *read_rest(int fd, const void *head, size_t n, const char *path, const char *name);

tex_map *tex_map_read_memory(const void *data, size_t len, const char *name)
{
    return nonfinite(decode(NULL, data, len, name), name);
}

tex_map *tex_map_read(const char *path)
{
    tex_buf b = {0};
    tex_map *m = NULL;
    int fd = 0;
    const char *name = "standard input";

    struct stat st;

    if (path && strcmp(path, "-") != 0 && (tex_format_from_name(path) == TEX_FMT_PROSIM ||
                                           tex_format_from_name(path) == TEX_FMT_PIC))
        return nonfinite(tex_prosim_read(path), path); /* no magic: the name says it */
    if (path && strcmp(path, "-") != 0) {
        name = path;
        if ((fd = open(path, O_RDONLY)) < 0) {
            tex_error("%s: %s", path, strerror(errno));
            return NULL;
        }
    } else {
        path = NULL;
        /* It would wait silently for keystrokes. */
        if (isatty(0)) {
            tex_usage_error("standard input: refusing to read image data from a terminal; "
                            "give a file or a pipe");
            return NULL;
        }
    }
    /* A pipe carrying the stream is decoded as it arrives; anything else
     * (a file, another format) is read whole first. */
    if (fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode)) {
        unsigned char head[64];
        size_t n = 0;
        while (n < sizeof head) {
            ssize_t k = read(fd, head + n, sizeof head - n);
            if (k < 0 && errno == EINTR)
                continue;
            if (k <= 0) {
                if (k < 0) {
                    tex_error("%s: %s", name, strerror(errno));
                    goto done;
                }
                break;
            }
            n += (size_t)k;
        }
        if (tex_format_sniff(head, n) == TEX_FMT_EXR) {
            if (!(m = tex_exr_read_fd(fd, head, n, name)))
                tex_error_context(name);
            goto done;
        }
        m = read_rest(fd, head, n, path, name);
        goto done;
    }
    if (tex_read_fd(fd, &b, name) == 0)
        m = decode(path, b.data, b.len, name);
done:
    if (fd != 0)
        close(fd);
    tex_buf_free(&b);
    return nonfinite(m, name);
}

/* A pipe's map whose first n bytes were read into head. */
static tex_map *read_rest(int fd, const void *head, size_t n, const char *path, const char *name)
{
    tex_buf b = {0};
    tex_map *m = NULL;

    if (tex_buf_reserve(&b, 1 << 20) == 0) {
        memcpy(b.data, head, n);
        b.len = n;
        if (tex_read_fd(fd, &b, name) == 0)
            m = decode(path, b.data, b.len, name);
    }
    tex_buf_free(&b);
    return m;
}

/* The pipe fd (standard input, or a FIFO named on the command line, closed here or by
 * tex_rows_close) opened for rows, or read whole into *whole */
static tex_rows_reader *open_pipe_rows(int fd, const char *name, tex_map *head, tex_map **whole)
{
    unsigned char pre[64];
    size_t n = 0;
    tex_rows_reader *r = NULL;
    tex_map *m = NULL;
    int failed = 0;

    while (n < sizeof pre && !failed) {
        ssize_t k = read(fd, pre + n, sizeof pre - n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            failed = k < 0 ? tex_error("%s: %s", name, strerror(errno)) : 0;
        if (k <= 0)
            break;
        n += (size_t)k;
    }
    if (failed)
        ;
    else if (tex_format_sniff(pre, n) != TEX_FMT_EXR)
        *whole = nonfinite(read_rest(fd, pre, n, NULL, name), name);
    else if (!(r = tex_rows_open(fd, pre, n, NULL, name, head, &m)) && m)
        *whole = nonfinite(m, name); /* tiled: decoded whole from what the pipe had sent */
    if (!r && fd != 0)
        close(fd);
    return r;
}

int tex_rows_whole(void)
{
    const char *e = getenv("TEXTURA_BAND_ROWS");
    return e && !strcmp(e, "whole");
}

tex_rows_reader *tex_map_open_rows(const char *path, tex_map *head, tex_map **whole)
{
    const char *name = path && strcmp(path, "-") ? path : "standard input";
    unsigned char pre[4];
    struct stat st;
    tex_rows_reader *r;

    *whole = NULL;
    if (tex_rows_whole()) {
        *whole = tex_map_read(path);
        return NULL;
    }
    /* a file on standard input, read from its start: by its name, as a file given is */
    if ((!path || !strcmp(path, "-")) && !isatty(0) && fstat(0, &st) == 0 &&
        S_ISREG(st.st_mode) && lseek(0, 0, SEEK_CUR) == 0)
        path = "/dev/stdin"; /* a new open: standard input's own offset stays at 0 */
    if (path && strcmp(path, "-") != 0) {
        int fd = open(path, O_RDONLY);
        size_t max;
        if (fd < 0) {
            tex_error("%s: %s", name, strerror(errno));
            return NULL;
        }
        if (fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode))
            return open_pipe_rows(fd, name, head, whole); /* <(t_noise ...) */
        /* a file over the input limit of a read in rows (any map's, unless set), or not a
         * regular one (a device): the whole reader refuses it with its words, or counts the
         * bytes it reads */
        int plain = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) &&
                    tex_input_max_rows(TEX_MAP_MAX_SIDE, TEX_MAP_MAX_SIDE, TEX_MAP_MAX_CHANNELS,
                                       0, &max) == 0 &&
                    (unsigned long long)st.st_size <= max && read(fd, pre, 4) == 4;
        close(fd);
        if (plain && tex_format_sniff(pre, 4) == TEX_FMT_EXR &&
            (r = tex_rows_open(-1, NULL, 0, path, name, head, NULL)))
            return r;
        /* another format, a tiled EXR, or refused */
        *whole = tex_map_read(strcmp(name, "standard input") ? path : NULL);
        return NULL;
    }
    if (isatty(0) || fstat(0, &st) != 0 || !S_ISFIFO(st.st_mode)) {
        *whole = tex_map_read(NULL); /* a file on standard input: as tex_map_read does */
        return NULL;
    }
    return open_pipe_rows(0, name, head, whole);
}

/* ---- writing ---- */

/* v clamped to [0,1] (NaN to 0), times scale, rounded as lrintf rounds: below 2^23, adding
 * 2^23 leaves no fraction, so the sum is rounded in the current mode and the difference is
 * exact.  Unlike lrintf (a call to libm, errno aside) it vectorises. */
static inline float quantum(float v, float scale)
{
    v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN fails v > 0 */
    return v * scale + 0x1p23f - 0x1p23f;
}

/* Quantise m's samples to 8 or 16 bits with clamping and rounding into q. */
static void quantise_to(const tex_map *m, int bits, void *q)
{
    size_t n = tex_map_samples(m);
    const float *px = m->px;

    if (bits == 8) {
        unsigned char *o = q;
#pragma omp simd
        for (size_t i = 0; i < n; i++)
            o[i] = (unsigned char)(int)quantum(px[i], 255.0f);
    } else {
        unsigned short *o = q;
#pragma omp simd
        for (size_t i = 0; i < n; i++)
            o[i] = (unsigned short)(int)quantum(px[i], 65535.0f);
    }
}

/* m's samples as 8- or 16-bit integers, in memory of tex_pages_new's (*mapped for
 * tex_pages_free): on the heap a 2048^2 map's were a first touch of 1,000 pages. */
static void *quantise(const tex_map *m, int bits, size_t *mapped)
{
    void *q = tex_pages_new(tex_map_samples(m) * (bits / 8), PAGES_FROM, mapped);

    if (!q) {
        tex_error("out of memory");
        return NULL;
    }
    quantise_to(m, bits, q);
    return q;
}

static int choose_depth(enum tex_format f, int depth, const char *name)
{
    if (f == TEX_FMT_EXR || f == TEX_FMT_PFM || f == TEX_FMT_HDR) {
        if (depth != 0 && depth != 32)
            return tex_usage_error("%s: %s holds float samples only (--depth 32)", name,
                                   tex_format_name(f));
        return 32;
    }
    if (depth == 0)
        return 8;
    if (depth == 32 && !formats[f].float_ok)
        return tex_usage_error("%s: %s cannot hold float samples (use exr, tif, pfm or hdr)", name,
                               tex_format_name(f));
    if (depth == 16 && formats[f].max_int_depth < 16)
        return tex_usage_error("%s: %s holds 8-bit samples only", name, tex_format_name(f));
    return depth;
}

/* A copy of m with a channel count format f can hold: grey becomes RGB,
 * a 2-vector (R,G) gains B = 0, alpha is added (1) or dropped. */
static tex_map *adapt_channels(const tex_map *m, enum tex_format f)
{
    static const int prefer[5][3] = {{0}, {3, 4, 0}, {3, 4, 1}, {4, 1, 0}, {3, 1, 0}};
    int nc = 0;
    tex_map *a;

    for (int i = 0; i < 3 && !nc; i++)
        if (prefer[m->nc][i] && formats[f].nc_ok & (1u << (prefer[m->nc][i] - 1)))
            nc = prefer[m->nc][i];
    if (!nc) {
        tex_error("%s cannot hold %d channels", tex_format_name(f), m->nc);
        return NULL;
    }
    if (!(a = tex_map_new(m->w, m->h, nc)))
        return NULL;
    for (size_t i = 0, n = (size_t)m->w * m->h; i < n; i++) {
        const float *s = m->px + i * m->nc;
        float *d = a->px + i * nc, rgba[4] = {s[0], s[0], s[0], 1.0f};
        if (m->nc >= 2) {
            rgba[1] = s[1];
            rgba[2] = m->nc >= 3 ? s[2] : 0.0f;
            rgba[3] = m->nc == 4 ? s[3] : 1.0f;
        }
        if (nc == 1) /* colour to grey as ppmtopgm weighs it */
            d[0] = m->nc >= 3 ? 0.299f * s[0] + 0.587f * s[1] + 0.114f * s[2] : s[0];
        else
            for (int c = 0; c < nc; c++)
                d[c] = rgba[c];
    }
    return a;
}

/* Write m in format f to the file at tmp (already created); name is for messages. */
static int write_to_path(const tex_map *m, enum tex_format f, int depth, const char *tmp, int fd,
                         const struct tex_write_opts *o, const char *name)
{
    if (!(formats[f].nc_ok & (1u << (m->nc - 1)))) {
        tex_map *a = adapt_channels(m, f);
        int r;
        if (!a) {
            tex_error_context(name);
            return -1;
        }
        r = write_to_path(a, f, depth, tmp, fd, o, name);
        tex_map_free(a);
        return r;
    }
    if (f == TEX_FMT_PFM)
        return tex_pfm_write_fd(m, fd, name);
    if (is_netpbm(f))
        return tex_pnm_write_fd(m, fd, depth,
                                f == TEX_FMT_PAM   ? TEX_PNM_PAM
                                : f == TEX_FMT_PBM ? TEX_PNM_PBM
                                                   : TEX_PNM_AUTO,
                                name);
    if (f == TEX_FMT_EXR) {
        tex_buf b = {0};
        int r;
        if (o->tiled || o->mipmap)
            r = tex_exr_encode_tiled(m, TEX_EXR_TILE, o->mipmap,
                                     fd == 1 ? TEX_COMPRESS_NONE : o->compression, &b);
        else if (fd == 1 || o->compression == TEX_COMPRESS_NONE)
            return tex_exr_write_fd(m, fd, name);
        else
            r = tex_exr_encode(m, o->compression, &b);
        if (r == 0)
            r = tex_write_all(fd, b.data, b.len, name);
        tex_buf_free(&b);
        return r;
    } else if (codec_slot(f)) {
        const struct tex_codec_bridge *br = bridge_load(codec_slot(f));
        char err[400] = "";
        void *px;
        size_t mapped = 0;
        int r;

        if (!br) {
            tex_error_context(name);
            return -1;
        }
        if (!(px = depth == 32 ? m->px : quantise(m, depth, &mapped)))
            return -1;
        r = br->write(fd, px, m->w, m->h, m->nc, depth, err, sizeof err);
        if (depth != 32)
            tex_pages_free(px, mapped);
        return r < 0 ? tex_error("%s: %s", name, err) : 0;
    } else {
        const struct tex_oiio_bridge *br = bridge();
        char err[400] = "";
        size_t mapped = 0;
        void *px = depth == 32 ? m->px : quantise(m, depth, &mapped);
        int r;

        if (!br) {
            if (depth != 32)
                tex_pages_free(px, mapped);
            tex_error_context(name);
            return -1;
        }
        if (!px)
            return -1;
        r = br->write(tmp, tex_format_name(f), px, m->w, m->h, m->nc, depth, err, sizeof err);
        if (depth != 32)
            tex_pages_free(px, mapped);
        if (r < 0)
            return tex_error("%s: %s", name, err);
        return 0;
    }
}

/* ---- outputs: atomic files, and what a signal leaves behind ---- */

/* The temporary files alive now, for the signal handler: it may only read
 * these (async-signal-safe), so each path is copied in before its flag is set. */
#define TEMP_SLOTS 4
static char temp_path[TEMP_SLOTS][PATH_MAX];
static volatile sig_atomic_t temp_used[TEMP_SLOTS];
static const int temp_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

static void on_signal(int sig)
{
    int saved = errno;
    sigset_t one;

    for (int i = 0; i < TEMP_SLOTS; i++)
        if (temp_used[i])
            unlink(temp_path[i]);
    /* The four signals stay blocked in this thread while it runs (sa_mask):
     * a second one (timeout(1) signals the child, then its group) cannot end
     * the process before the unlink.  Then the default action, and the
     * signal again, delivered once unblocked: the process ends as it would have. */
    signal(sig, SIG_DFL);
    raise(sig);
    sigemptyset(&one);
    sigaddset(&one, sig);
    sigprocmask(SIG_UNBLOCK, &one, NULL);
    errno = saved;
}

/* Catch the signals once, leaving alone those the parent ignores (nohup). */
static void catch_signals(void)
{
    static int done;
    struct sigaction sa;

    if (done)
        return;
    done = 1;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < sizeof temp_signals / sizeof *temp_signals; i++)
        sigaddset(&sa.sa_mask, temp_signals[i]);
    for (size_t i = 0; i < sizeof temp_signals / sizeof *temp_signals; i++) {
        struct sigaction old;
        if (sigaction(temp_signals[i], NULL, &old) == 0 && old.sa_handler == SIG_DFL)
            sigaction(temp_signals[i], &sa, NULL);
    }
}

/* Record a temporary file for removal on a signal, before it exists: the name is
 * made in its slot (mkstemp fills in the template there), so that a signal
 * taken by any thread at any moment finds it.  The slot, or -1 when all are taken. */
static int temp_record(const char *tmpl)
{
    catch_signals();
    for (int i = 0; i < TEMP_SLOTS; i++)
        if (!temp_used[i]) {
            snprintf(temp_path[i], sizeof temp_path[i], "%s", tmpl);
            __atomic_signal_fence(__ATOMIC_SEQ_CST); /* the path before the flag */
            temp_used[i] = 1;
            return i;
        }
    return -1;
}

static void temp_forget(int slot)
{
    if (slot >= 0)
        temp_used[slot] = 0;
}

/* A temporary file made from the template tmp (mkstemp), recorded. */
static int temp_create(char *tmp, int *slot)
{
    sigset_t all, old;
    int fd;

    /* No signal in this thread meanwhile; another thread that takes one finds
     * the slot set already (unlinking a name not made yet does no harm). */
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old);
    if ((*slot = temp_record(tmp)) >= 0) {
        fd = mkstemp(temp_path[*slot]);
        snprintf(tmp, PATH_MAX, "%s", temp_path[*slot]);
        if (fd < 0) {
            temp_used[*slot] = 0;
            *slot = -1;
        }
    } else {
        fd = mkstemp(tmp);
    }
    sigprocmask(SIG_SETMASK, &old, NULL);
    return fd;
}

/* The file a chain of symbolic links ends at (the path itself if it is
 * none); a relative target is taken from the link's folder. */
static int resolve_links(const char *path, char *out, size_t n)
{
    char cur[PATH_MAX], target[PATH_MAX];

    if ((size_t)snprintf(cur, sizeof cur, "%s", path) >= sizeof cur)
        return tex_error("%s: path too long", path);
    for (int hops = 0;; hops++) {
        struct stat st;
        ssize_t k;
        if (lstat(cur, &st) < 0 || !S_ISLNK(st.st_mode))
            break;
        if (hops == 40)
            return tex_error("%s: too many levels of symbolic links", path);
        if ((k = readlink(cur, target, sizeof target - 1)) < 0)
            return tex_error("%s: %s", path, strerror(errno));
        target[k] = '\0';
        if (target[0] == '/' || !strrchr(cur, '/')) {
            memcpy(cur, target, (size_t)k + 1);
        } else {
            char *slash = strrchr(cur, '/');
            if ((size_t)(slash - cur) + 2 + (size_t)k > sizeof cur)
                return tex_error("%s: path too long", path);
            memcpy(slash + 1, target, (size_t)k + 1);
        }
    }
    if ((size_t)snprintf(out, n, "%s", cur) >= n)
        return tex_error("%s: path too long", path);
    return 0;
}

int tex_out_open(struct tex_out *o, const char *path)
{
    struct stat st;
    const char *slash;
    int r;

    memset(o, 0, sizeof *o);
    o->fd = -1;
    o->slot = -1;
    o->name = path;
    /* /dev/fd/N is descriptor N as the shell opened it (appending, say), not reopened */
    if (strncmp(path, "/dev/fd/", 8) == 0 && path[8] >= '0' && path[8] <= '9') {
        char *end;
        long n = strtol(path + 8, &end, 10);
        o->direct = 1;
        if (*end || n > INT_MAX || (o->fd = fcntl((int)n, F_DUPFD_CLOEXEC, 3)) < 0)
            return tex_error("%s: %s", path, *end ? "not a descriptor" : strerror(errno));
        return 0;
    }
    /* A FIFO or a device is written straight: renaming only makes sense for files. */
    if (stat(path, &st) == 0 && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode))) {
        o->direct = 1;
        if ((o->fd = open(path, O_WRONLY | O_CLOEXEC)) < 0)
            return tex_error("%s: %s", path, strerror(errno));
        return 0;
    }
    /* A symbolic link keeps pointing at its target, which is replaced atomically. */
    if (resolve_links(path, o->path, sizeof o->path) < 0)
        return -1;
    if (stat(o->path, &st) == 0 && S_ISREG(st.st_mode)) {
        o->mode = st.st_mode & 07777;
    } else {
        mode_t mask = umask(0);
        umask(mask);
        o->mode = 0666 & ~mask;
    }
    slash = strrchr(o->path, '/');
    if (slash)
        r = snprintf(o->tmp, sizeof o->tmp, "%.*s/.%s.XXXXXX", (int)(slash - o->path), o->path,
                     slash + 1);
    else
        r = snprintf(o->tmp, sizeof o->tmp, ".%s.XXXXXX", o->path);
    if (r < 0 || (size_t)r >= sizeof o->tmp)
        return tex_error("%s: path too long", path);
    if ((o->fd = temp_create(o->tmp, &o->slot)) < 0) {
        o->tmp[0] = '\0'; /* nothing to remove */
        return tex_error("%s: cannot create a file there: %s", path, strerror(errno));
    }
    return 0;
}

int tex_out_close(struct tex_out *o, int r)
{
    if (o->fd >= 0 && close(o->fd) < 0 && r == 0)
        r = tex_error("%s: %s", o->name, strerror(errno));
    o->fd = -1;
    if (o->direct || !o->tmp[0])
        return r;
    if (r == 0) {
        /* mkstemp makes the file 0600: give it the mode of the file it
         * replaces, or the one a new file would get. */
        chmod(o->tmp, o->mode);
        if (rename(o->tmp, o->path) < 0)
            r = tex_error("%s: %s", o->name, strerror(errno));
    }
    if (r < 0)
        unlink(o->tmp);
    temp_forget(o->slot);
    return r;
}

/* Write m to fd, which may not seek (standard output, a FIFO). */
static int write_stream(const tex_map *m, enum tex_format f, int depth, int fd,
                        const struct tex_write_opts *o, const char *name)
{
    int r;

    /* These writers stream; TIFF seeks and OpenImageIO writes files: they go
     * through a temporary one. */
    if (f != TEX_FMT_TIFF && (f == TEX_FMT_EXR || f == TEX_FMT_PFM || is_netpbm(f) ||
                              codec_slot(f)))
        return write_to_path(m, f, depth, NULL, fd, o, name);
    {
        const char *dir = getenv("TMPDIR");
        char path[PATH_MAX];
        tex_buf b = {0};
        int tfd, slot = -1;

        snprintf(path, sizeof path, "%s/textura.XXXXXX", dir && *dir ? dir : "/tmp");
        if ((tfd = temp_create(path, &slot)) < 0)
            return tex_error("cannot create a temporary file in %s: %s", dir ? dir : "/tmp",
                             strerror(errno));
        r = write_to_path(m, f, depth, path, tfd, o, name);
        if (r == 0 && lseek(tfd, 0, SEEK_SET) == 0 && (r = tex_read_fd(tfd, &b, path)) == 0)
            r = tex_write_all(fd, b.data, b.len, name);
        tex_buf_free(&b);
        close(tfd);
        unlink(path);
        temp_forget(slot);
        return r;
    }
}

int tex_map_write_check(const char *path, const char *format)
{
    const char *file;
    struct stat st;

    if (tex_output_format(path, format, &file) == TEX_FMT_UNKNOWN)
        return -1;
    if (!file)
        return isatty(1) ? tex_usage_error("refusing to write image data to a terminal; use -o "
                                           "FILE or a pipe")
                         : 0;
    if (stat(file, &st) == 0 && S_ISDIR(st.st_mode))
        return tex_error("%s: is a directory", file);
    if (stat(file, &st) == 0 && S_ISCHR(st.st_mode)) {
        int fd = open(file, O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC), tty = isatty(fd);
        if (fd >= 0)
            close(fd);
        if (tty)
            return tex_usage_error("%s: refusing to write image data to a terminal", file);
    }
    return 0;
}

tex_map **tex_map_read_levels(const char *path, int *n)
{
    tex_map **lv = NULL, *m;
    int fd = -1;
    tex_buf b = {0};
    unsigned char head[4];

    *n = 0;
    if (!path || strcmp(path, "-") == 0 || (fd = open(path, O_RDONLY)) < 0 ||
        read(fd, head, 4) != 4 || tex_format_sniff(head, 4) != TEX_FMT_EXR ||
        lseek(fd, 0, SEEK_SET) != 0 || tex_read_fd(fd, &b, path) < 0 ||
        tex_exr_unsupported(b.data, b.len)) {
        /* not a whole EXR file: one level, read as any map */
        if (path && strcmp(path, "-") != 0 && fd >= 0)
            close(fd);
        tex_buf_free(&b);
        if (!(m = tex_map_read(path)))
            return NULL;
        if (!(lv = malloc(sizeof *lv))) {
            tex_map_free(m);
            tex_error("out of memory");
            return NULL;
        }
        lv[0] = m;
        *n = 1;
        return lv;
    }
    close(fd);
    lv = tex_exr_decode_levels(b.data, b.len, path, n);
    tex_buf_free(&b);
    if (!lv) {
        tex_error_context(path);
        return NULL;
    }
    for (int l = 0; l < *n; l++)
        if (!nonfinite(lv[l], path)) { /* it freed that level */
            for (int k = 0; k < *n; k++)
                if (k != l)
                    tex_map_free(lv[k]);
            free(lv);
            return NULL;
        }
    return lv;
}

int tex_map_write(const tex_map *m, const char *path, const struct tex_write_opts *o)
{
    static const struct tex_write_opts defaults = TEX_WRITE_DEFAULTS;
    struct tex_out out;
    const char *file;
    enum tex_format f;
    int depth, r;

    if (!o)
        o = &defaults;
    if (tex_map_write_check(path, o->format) < 0)
        return -1;
    f = tex_output_format(path, o->format, &file);
    if ((depth = choose_depth(f, o->depth, file ? file : "standard output")) < 0)
        return -1;
    if (f == TEX_FMT_PROSIM || f == TEX_FMT_PIC) { /* files of their own, no stream */
        tex_map *a = NULL;
        if (!file)
            return tex_usage_error("standard output: ProSim's .%s files have no header to "
                                   "stream; name the file", tex_format_name(f));
        if (!(formats[f].nc_ok & (1u << (m->nc - 1))) && !(a = adapt_channels(m, f))) {
            tex_error_context(file);
            return -1;
        }
        r = tex_prosim_write(a ? a : m, file, f == TEX_FMT_PIC, file);
        tex_map_free(a);
        return r;
    }
    if (!file)
        return write_stream(m, f, depth, 1, o, "standard output");
    if (tex_out_open(&out, file) < 0)
        return tex_out_close(&out, -1);
    r = out.direct ? write_stream(m, f, depth, out.fd, o, file)
                   : write_to_path(m, f, depth, out.tmp, out.fd, o, file);
    return tex_out_close(&out, r);
}

/* ---- writing a band of rows at a time ---- */

/* Where o sends a map: the format, the file (NULL: standard output), and whether the
 * output can seek (a regular file, not a FIFO or a device).  TEX_FMT_UNKNOWN with the
 * error set. */
static enum tex_format rows_target(const char *path, const struct tex_write_opts *o,
                                   const char **file, int *seeks)
{
    struct stat st;
    enum tex_format f = tex_output_format(path, o->format, file);

    *seeks = *file && strncmp(*file, "/dev/fd/", 8) &&
             (stat(*file, &st) != 0 || S_ISREG(st.st_mode));
    return f;
}

int tex_map_write_streams(const char *path, const struct tex_write_opts *o)
{
    int seeks;
    const char *file;
    enum tex_format f = rows_target(path, o, &file, &seeks);

    switch (f) {
    case TEX_FMT_EXR:
        return !o->mipmap && (!o->tiled || seeks); /* tiles go at their offsets */
    case TEX_FMT_PNG: case TEX_FMT_JPEG: case TEX_FMT_PNM: case TEX_FMT_PAM: case TEX_FMT_PBM:
    case TEX_FMT_PPM: case TEX_FMT_PGM:
        return 1;
    case TEX_FMT_TIFF: case TEX_FMT_PFM: /* TIFF seeks; PFM's rows run bottom to top */
        return seeks;
    default:
        return 0; /* OpenImageIO's writers take the whole map */
    }
}

/* A map's rows on their way to a file of another format than EXR: fill's rows of head's
 * channels into band, adapted to the file's channels (adapt_channels, as the whole map's)
 * and, for a codec, quantised to depth bits. */
struct rows_out {
    tex_rows_fn fill;
    void *arg;
    enum tex_format f;
    int depth, h, fd, pfm_head;
    tex_map *band;
    const char *name;
};

/* Rows y..y+n-1 of fill's in s->band, adapted: the band, or a new map to free (*adapted) */
static const tex_map *out_band(struct rows_out *s, int y, int n, tex_map **adapted)
{
    s->band->h = n;
    *adapted = NULL;
    if (s->fill(s->arg, y, n, s->band->px) < 0)
        return NULL;
    if (formats[s->f].nc_ok & (1u << (s->band->nc - 1)))
        return s->band;
    if (!(*adapted = adapt_channels(s->band, s->f)))
        tex_error_context(s->name);
    return *adapted;
}

static int codec_rows(void *arg, int y, int n, void *dst)
{
    struct rows_out *s = arg;
    tex_map *a;
    const tex_map *b = out_band(s, y, n, &a);

    if (!b)
        return -1;
    if (s->depth == 32)
        memcpy(dst, b->px, tex_map_samples(b) * sizeof(float));
    else
        quantise_to(b, s->depth, dst);
    tex_map_free(a);
    return 0;
}

/* The file after its header, a band of TEX_CODEC_BAND rows at a time */
static int netpbm_rows(struct rows_out *s)
{
    enum tex_pnm_variant v = s->f == TEX_FMT_PAM ? TEX_PNM_PAM
                             : s->f == TEX_FMT_PBM ? TEX_PNM_PBM : TEX_PNM_AUTO;
    int r = 0;

    for (int y = 0; y < s->h && r == 0; y += TEX_CODEC_BAND) {
        tex_map *a;
        const tex_map *b = out_band(s, y, s->h - y < TEX_CODEC_BAND ? s->h - y : TEX_CODEC_BAND, &a);
        r = !b ? -1
            : s->f == TEX_FMT_PFM ? tex_pfm_write_band(b, y, s->h, s->pfm_head, s->fd, s->name)
                                  : tex_pnm_write_band(b, s->fd, s->depth, v, s->name);
        tex_map_free(a);
    }
    return r;
}

/* head's rows from fill in format f (not EXR) to fd */
static int write_rows_as(const tex_map *head, struct rows_out *s)
{
    int nc = head->nc;

    if (!(formats[s->f].nc_ok & (1u << (nc - 1)))) { /* the channels the file will hold */
        tex_map one = *head;
        one.w = one.h = 1;
        float px[4] = {0};
        one.px = px;
        tex_map *a = adapt_channels(&one, s->f);
        if (!a) {
            tex_error_context(s->name);
            return -1;
        }
        nc = a->nc;
        tex_map_free(a);
    }
    if (!(s->band = tex_map_new(head->w, TEX_CODEC_BAND, head->nc)))
        return -1;
    if (codec_slot(s->f)) {
        const struct tex_codec_bridge *br = bridge_load(codec_slot(s->f));
        char err[400] = "";
        if (!br) {
            tex_error_context(s->name);
            return -1;
        }
        if (br->write_rows(s->fd, head->w, head->h, nc, s->depth, codec_rows, s, err,
                           sizeof err) < 0)
            return strcmp(err, "rows") ? tex_error("%s: %s", s->name, err) : -1;
        return 0;
    }
    if (s->f == TEX_FMT_PFM)
        s->pfm_head = tex_pfm_write_head(head->w, head->h, nc, s->fd, s->name);
    else
        s->pfm_head = tex_pnm_write_head(head->w, head->h, nc, s->fd, s->depth,
                                         s->f == TEX_FMT_PAM   ? TEX_PNM_PAM
                                         : s->f == TEX_FMT_PBM ? TEX_PNM_PBM
                                                               : TEX_PNM_AUTO,
                                         s->name);
    return s->pfm_head < 0 ? -1 : netpbm_rows(s);
}

int tex_map_write_rows(const tex_map *head, tex_rows_fn fill, void *arg, const char *path,
                       const struct tex_write_opts *o)
{
    return tex_map_write_rows_at(head, fill, NULL, arg, path, o);
}

int tex_map_write_rows_at(const tex_map *head, tex_rows_fn fill, tex_rows_at_fn at, void *arg,
                          const char *path, const struct tex_write_opts *o)
{
    static const struct tex_write_opts defaults = TEX_WRITE_DEFAULTS;
    struct tex_out out = {.fd = 1};
    const char *name, *file;
    int seeks, depth, r;
    enum tex_format f;

    if (!o)
        o = &defaults;
    if (tex_map_write_check(path, o->format) < 0)
        return -1;
    f = rows_target(path, o, &file, &seeks);
    name = file ? file : "standard output";
    if ((depth = choose_depth(f, o->depth, name)) < 0)
        return -1;
    if (!tex_map_write_streams(path, o))
        return tex_usage_error("%s: %s is written whole, not a band of rows at a time", name,
                               tex_format_name(f));
    if (file && tex_out_open(&out, file) < 0)
        return tex_out_close(&out, -1);
    if (f == TEX_FMT_EXR) {
        /* standard output carries the stream, never compressed, a regular file or not, as
         * tex_map_write writes it */
        r = tex_exr_write_rows_at(head, fill, at, arg, o->tiled ? TEX_EXR_TILE : 0,
                                  out.fd == 1 ? TEX_COMPRESS_NONE : o->compression, out.fd, name);
    } else {
        struct rows_out s = {fill, arg, f, depth, head->h, out.fd, 0, NULL, name};
        r = write_rows_as(head, &s);
        tex_map_free(s.band);
    }
    return out.fd == 1 ? r : tex_out_close(&out, r);
}
