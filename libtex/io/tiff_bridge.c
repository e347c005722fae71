/* tiff_bridge.c - TIFF through libtiff, built as textura-tiff.so (see codec_bridge.h)
 *
 * Grey and RGB files of 8 or 16-bit integers or 32-bit floats, in strips or
 * tiles, with samples interleaved, are read as stored: the first four
 * samples of a pixel (a warning is the caller's).  Any other layout
 * (palette, bilevel, YCbCr, CMYK, separate planes) goes through libtiff's
 * RGBA reader, 8 bits.  Written files are deflate-compressed with the
 * horizontal (integers) or floating-point predictor; a 4th channel is
 * unassociated alpha, a 2nd one an unspecified extra sample (a 2-vector's
 * second component, not alpha).
 */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <tiffio.h>

#include "io/codec_bridge.h"

static char last_error[300];

static void on_error(const char *module, const char *fmt, va_list ap)
{
    (void)module;
    vsnprintf(last_error, sizeof last_error, fmt, ap);
}

struct memsrc {
    const unsigned char *p;
    toff_t len, off;
};

static tmsize_t m_read(thandle_t h, void *buf, tmsize_t n)
{
    struct memsrc *m = h;
    toff_t k = m->off < m->len ? m->len - m->off : 0;
    if ((toff_t)n < k)
        k = (toff_t)n;
    memcpy(buf, m->p + m->off, (size_t)k);
    m->off += k;
    return (tmsize_t)k;
}

static tmsize_t m_write(thandle_t h, void *buf, tmsize_t n)
{
    (void)h;
    (void)buf;
    (void)n;
    return -1;
}

static toff_t m_seek(thandle_t h, toff_t off, int whence)
{
    struct memsrc *m = h;
    m->off = whence == SEEK_SET ? off : whence == SEEK_CUR ? m->off + off : m->len + off;
    return m->off;
}

static int m_close(thandle_t h)
{
    (void)h;
    return 0;
}

static toff_t m_size(thandle_t h)
{
    return ((struct memsrc *)h)->len;
}

struct layout {
    uint32_t w, h;
    uint16_t spp, bps, fmt, photo, planar;
    int native, nc;
};

static void say(char *err, size_t errlen, const char *fallback)
{
    snprintf(err, errlen, "%s", last_error[0] ? last_error : fallback);
}

static TIFF *open_mem(struct memsrc *src, struct layout *l, char *err, size_t errlen)
{
    TIFF *t;
    uint16_t extra = 0, *types;

    TIFFSetErrorHandler(on_error);
    TIFFSetWarningHandler(NULL);
    last_error[0] = '\0';
    if (!(t = TIFFClientOpen("tiff", "rm", src, m_read, m_write, m_seek, m_close, m_size, NULL,
                             NULL))) {
        snprintf(err, errlen, "bad TIFF file (%s)", last_error[0] ? last_error : "unreadable");
        return NULL;
    }
    TIFFGetFieldDefaulted(t, TIFFTAG_IMAGEWIDTH, &l->w);
    TIFFGetFieldDefaulted(t, TIFFTAG_IMAGELENGTH, &l->h);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &l->spp);
    TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &l->bps);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &l->fmt);
    TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &l->planar);
    TIFFGetFieldDefaulted(t, TIFFTAG_EXTRASAMPLES, &extra, &types);
    if (!TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &l->photo))
        l->photo = l->spp >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK;
    if (l->w == 0 || l->h == 0 || l->spp == 0) {
        snprintf(err, errlen, "TIFF %s is 0", l->w == 0 ? "width" : l->h == 0 ? "height" : "samples per pixel");
        TIFFClose(t);
        return NULL;
    }
    l->native = (l->photo == PHOTOMETRIC_MINISBLACK || l->photo == PHOTOMETRIC_RGB) &&
                (l->spp == 1 || l->planar == PLANARCONFIG_CONTIG) &&
                (((l->bps == 8 || l->bps == 16) && l->fmt == SAMPLEFORMAT_UINT) ||
                 (l->bps == 32 && l->fmt == SAMPLEFORMAT_IEEEFP));
    if (l->native)
        l->nc = l->spp < 4 ? l->spp : 4;
    else
        l->nc = extra > 0 ? 4 : 3;
    return t;
}

static int b_info(const void *mem, size_t len, int *w, int *h, int *nc, char *err, size_t errlen)
{
    struct memsrc src = {mem, len, 0};
    struct layout l;
    TIFF *t = open_mem(&src, &l, err, errlen);

    if (!t)
        return -1;
    if (l.w > INT32_MAX || l.h > INT32_MAX) {
        snprintf(err, errlen, "TIFF size %lux%lu is too large", (unsigned long)l.w, (unsigned long)l.h);
        TIFFClose(t);
        return -1;
    }
    *w = (int)l.w;
    *h = (int)l.h;
    *nc = l.native ? l.spp : l.nc; /* the caller warns past four; read gives the first four */
    TIFFClose(t);
    return 0;
}

/* n pixels of spp interleaved samples into nc floats each. */
static void convert(const unsigned char *s, const struct layout *l, float *d, size_t n)
{
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < l->nc; c++) {
            size_t k = i * l->spp + (size_t)c;
            d[i * l->nc + c] = l->bps == 8    ? (float)s[k] / 255.0f
                               : l->bps == 16 ? (float)((const uint16_t *)s)[k] / 65535.0f
                                              : ((const float *)s)[k];
        }
}

/* The message of a failed read of the data, row the first row of the strip or tile that
 * failed (-1: unknown).  libtiff names the row it had before the first read, "Read error
 * at scanline 4294967295; got 226 bytes, expected 240000", and says the data ends early
 * only by its figures: a truncation is said as PNG, PNM and PFM say it. */
static void data_error(char *err, size_t errlen, long row)
{
    unsigned long got, want;
    const char *g = strstr(last_error, "got ");
    if (g && sscanf(g, "got %lu bytes, expected %lu", &got, &want) == 2 && got < want)
        snprintf(err, errlen, "truncated TIFF data at row %ld (%lu of %lu bytes)",
                 row < 0 ? 0 : row, got, want);
    else if (row >= 0)
        snprintf(err, errlen, "unreadable TIFF data at row %ld (%s)", row,
                 last_error[0] ? last_error : "no detail");
    else
        say(err, errlen, "unreadable TIFF data");
}

/* The samples as stored; -1 with *bad the first row of the strip or tile that failed. */
static int read_native(TIFF *t, const struct layout *l, float *px, long *bad)
{
    size_t row = (size_t)l->w * l->nc;

    if (TIFFIsTiled(t)) {
        uint32_t tw, th;
        unsigned char *buf;
        TIFFGetField(t, TIFFTAG_TILEWIDTH, &tw);
        TIFFGetField(t, TIFFTAG_TILELENGTH, &th);
        if (!tw || !th || !(buf = _TIFFmalloc(TIFFTileSize(t))))
            return -1;
        for (uint32_t y = 0; y < l->h; y += th)
            for (uint32_t x = 0; x < l->w; x += tw) {
                if (TIFFReadTile(t, buf, x, y, 0, 0) < 0) {
                    *bad = y;
                    _TIFFfree(buf);
                    return -1;
                }
                for (uint32_t ty = 0; ty < th && y + ty < l->h; ty++) {
                    uint32_t cw = x + tw <= l->w ? tw : l->w - x;
                    convert(buf + (size_t)ty * tw * l->spp * (l->bps / 8), l,
                            px + (size_t)(y + ty) * row + (size_t)x * l->nc, cw);
                }
            }
        _TIFFfree(buf);
    } else {
        unsigned char *buf = _TIFFmalloc(TIFFScanlineSize(t));
        if (!buf)
            return -1;
        for (uint32_t y = 0; y < l->h; y++) {
            if (TIFFReadScanline(t, buf, y, 0) < 0) {
                *bad = y;
                _TIFFfree(buf);
                return -1;
            }
            convert(buf, l, px + (size_t)y * row, l->w);
        }
        _TIFFfree(buf);
    }
    return 0;
}

static int read_rgba(TIFF *t, const struct layout *l, float *px)
{
    size_t n = (size_t)l->w * l->h;
    uint32_t *rgba = _TIFFmalloc((tmsize_t)(n * sizeof *rgba));

    if (!rgba)
        return -1;
    if (!TIFFReadRGBAImageOriented(t, l->w, l->h, rgba, ORIENTATION_TOPLEFT, 0)) {
        _TIFFfree(rgba);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < l->nc; c++)
            px[i * l->nc + c] = (float)(rgba[i] >> (8 * c) & 0xff) / 255.0f;
    _TIFFfree(rgba);
    return 0;
}

static int b_read(const void *mem, size_t len, float *px, char *err, size_t errlen)
{
    struct memsrc src = {mem, len, 0};
    struct layout l;
    TIFF *t = open_mem(&src, &l, err, errlen);
    long bad = -1;
    int r;

    if (!t)
        return -1;
    r = l.native ? read_native(t, &l, px, &bad) : read_rgba(t, &l, px);
    if (r < 0)
        data_error(err, errlen, bad);
    TIFFClose(t);
    return r;
}

/* Scanlines asked for TEX_CODEC_BAND at a time and written one by one, as before. */
static int b_write_rows(int fd, int w, int h, int nc, int bits,
                        int (*rows)(void *arg, int y, int n, void *dst), void *arg, char *err,
                        size_t errlen)
{
    int dfd = dup(fd);
    TIFF *t;
    size_t stride = (size_t)w * nc * (bits / 8);
    uint16_t extra = nc == 4 ? EXTRASAMPLE_UNASSALPHA : EXTRASAMPLE_UNSPECIFIED;
    unsigned char *band = NULL;
    int r = 0;

    TIFFSetErrorHandler(on_error);
    TIFFSetWarningHandler(NULL);
    last_error[0] = '\0';
    if (dfd < 0 || !(t = TIFFFdOpen(dfd, "tiff", "w"))) {
        if (dfd >= 0)
            close(dfd);
        say(err, errlen, "cannot start the TIFF writer");
        return -1;
    }
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, (uint32_t)w);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, (uint32_t)h);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, (uint16_t)nc);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, (uint16_t)bits);
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, bits == 32 ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, nc >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
    if (nc == 2 || nc == 4)
        TIFFSetField(t, TIFFTAG_EXTRASAMPLES, 1, &extra);
    TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    TIFFSetField(t, TIFFTAG_PREDICTOR, bits == 32 ? PREDICTOR_FLOATINGPOINT : PREDICTOR_HORIZONTAL);
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(t, 0));
    /* The predictor rewrites the row it is given: the band is a copy. */
    if (!(band = malloc(stride * TEX_CODEC_BAND)))
        r = -1;
    for (int y = 0; y < h && r == 0; y += TEX_CODEC_BAND) {
        int n = h - y < TEX_CODEC_BAND ? h - y : TEX_CODEC_BAND;
        if (rows(arg, y, n, band) < 0) {
            snprintf(last_error, sizeof last_error, "rows");
            r = -1;
        }
        for (int k = 0; k < n && r == 0; k++)
            if (TIFFWriteScanline(t, band + stride * (size_t)k, (uint32_t)(y + k), 0) < 0)
                r = -1;
    }
    if (r == 0 && !TIFFWriteDirectory(t))
        r = -1;
    free(band);
    TIFFClose(t);
    if (r < 0)
        say(err, errlen, "write error");
    return r;
}

static int b_write(int fd, const void *px, int w, int h, int nc, int bits, char *err,
                   size_t errlen)
{
    struct tex_codec_px p = {px, (size_t)w * nc * (bits / 8)};
    return b_write_rows(fd, w, h, nc, bits, tex_codec_copy_rows, &p, err, errlen);
}

__attribute__((visibility("default"))) const struct tex_codec_bridge tex_tiff_bridge = {
    TEX_CODEC_BRIDGE_VERSION, b_info, b_read, b_write, b_write_rows};
