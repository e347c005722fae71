/* prosim.c - ProSim's headerless texture files (see prosim.h) */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"
#include "io/file.h"
#include "io/limit.h"
#include "io/prosim.h"

int tex_prosim_size(const char *path, size_t npix, int *w, int *h)
{
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.'), *us = NULL;
    long long a, b;
    char tail;

    for (const char *p = base; dot && p < dot; p++)
        if (*p == '_')
            us = p;
    if (us && sscanf(us, "_%lldx%lld%c", &a, &b, &tail) == 3 && tail == '.' && a >= 1 &&
        b >= 1 && a <= TEX_MAP_MAX_SIDE && b <= TEX_MAP_MAX_SIDE) {
        if ((size_t)(a * b) != npix)
            return tex_error("%s: %zu pixels, not the %lldx%lld its name gives", path, npix, a, b);
        *w = (int)a, *h = (int)b;
        return 0;
    }
    long long s = llround(sqrt((double)npix));
    if (npix == 0 || s * s != (long long)npix || s > TEX_MAP_MAX_SIDE)
        return tex_error("%s: %zu pixels make no square, and the name gives no size (a "
                         "headerless ProSim file: name it NAME_WxH%s)",
                         path, npix, dot ? dot : "");
    *w = *h = (int)s;
    return 0;
}

tex_map *tex_prosim_decode(const void *data, size_t len, int pic, const char *path)
{
    const unsigned char *b = data;
    size_t npix = pic ? len / 4 : len;
    int w, h;
    tex_map *m;

    if (pic && len % 4) {
        tex_error("%s: %zu bytes, not whole 4-byte floats", path, len);
        return NULL;
    }
    if (tex_prosim_size(path, npix, &w, &h) < 0 || tex_input_check_decoded(w, h, 1) < 0 ||
        !(m = tex_map_new(w, h, 1)))
        return NULL;
    for (size_t i = 0; i < npix; i++) {
        if (pic) {
            uint32_t u = (uint32_t)b[4 * i] | (uint32_t)b[4 * i + 1] << 8 |
                         (uint32_t)b[4 * i + 2] << 16 | (uint32_t)b[4 * i + 3] << 24;
            memcpy(&m->px[i], &u, 4);
        } else {
            m->px[i] = b[i] / 255.0f;
        }
    }
    return m;
}

/* The file of path with its extension replaced by ext ("r", "g", "b") into out */
static int sibling(const char *path, const char *ext, char *out, size_t n)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    size_t base = dot && (!slash || dot > slash) ? (size_t)(dot - path) : strlen(path);
    int r = snprintf(out, n, "%.*s.%s", (int)base, path, ext);
    return r < 0 || (size_t)r >= n ? tex_error("%s: path too long", path) : 0;
}

static tex_map *read_one(const char *path, int pic)
{
    tex_buf b = {0};
    tex_map *m = NULL;
    int fd = open(path, O_RDONLY | O_CLOEXEC);

    if (fd < 0) {
        tex_error("%s: %s", path, strerror(errno));
        return NULL;
    }
    if (tex_read_fd(fd, &b, path) == 0)
        m = tex_prosim_decode(b.data, b.len, pic, path);
    close(fd);
    tex_buf_free(&b);
    return m;
}

tex_map *tex_prosim_read(const char *path)
{
    const char *dot = strrchr(path, '.');
    static const char *const ext[3] = {"r", "g", "b"};
    char name[4096];
    tex_map *c[3] = {NULL, NULL, NULL}, *m = NULL;

    if (dot && !strcmp(dot, ".pic"))
        return read_one(path, 1);
    for (int k = 0; k < 3; k++)
        if (sibling(path, ext[k], name, sizeof name) < 0 || !(c[k] = read_one(name, 0)))
            goto done;
    if (c[1]->w != c[0]->w || c[1]->h != c[0]->h || c[2]->w != c[0]->w || c[2]->h != c[0]->h) {
        tex_error("%s: its .r, .g and .b files differ in size", path);
        goto done;
    }
    if (!(m = tex_map_new(c[0]->w, c[0]->h, 3)))
        goto done;
    for (size_t i = 0, n = (size_t)m->w * m->h; i < n; i++)
        for (int k = 0; k < 3; k++)
            m->px[3 * i + k] = c[k]->px[i];
done:
    for (int k = 0; k < 3; k++)
        tex_map_free(c[k]);
    return m;
}

/* Channel k of m to fd: bytes, or little-endian floats */
static int write_channel(const tex_map *m, int k, int pic, int fd, const char *name)
{
    size_t n = (size_t)m->w * m->h, per = pic ? 4 : 1;
    unsigned char *buf = malloc(n * per);
    int r = 0;

    if (!buf)
        return tex_error("out of memory");
    for (size_t i = 0; i < n; i++) {
        float v = m->px[i * m->nc + k];
        if (pic) {
            uint32_t u;
            memcpy(&u, &v, 4);
            for (int j = 0; j < 4; j++)
                buf[4 * i + j] = (unsigned char)(u >> 8 * j);
        } else {
            v = v > 0 ? (v < 1 ? v : 1) : 0; /* NaN: 0 */
            buf[i] = (unsigned char)(v * 255 + 0.5f);
        }
    }
    for (size_t off = 0; off < n * per && r == 0;) {
        ssize_t w = write(fd, buf + off, n * per - off);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            r = tex_error("%s: %s", name, strerror(errno));
        else
            off += (size_t)w;
    }
    free(buf);
    return r;
}

int tex_prosim_write(const tex_map *m, const char *path, int pic, const char *name)
{
    static const char *const ext[3] = {"r", "g", "b"};
    struct tex_out out[3];
    char file[3][4096];
    int w, h, n = pic ? 1 : 3, r = 0, opened = 0;

    if (tex_prosim_size(path, (size_t)m->w * m->h, &w, &h) < 0 || w != m->w || h != m->h) {
        const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
        if (!dot || (slash && dot < slash))
            dot = path + strlen(path);
        return tex_usage_error("%s: a %dx%d map needs its size in the name, as ProSim's files "
                               "have no header: %.*s_%dx%d%s",
                               name, m->w, m->h, (int)(dot - path), path, m->w, m->h, dot);
    }
    for (int k = 0; k < n && r == 0; k++) {
        if (pic)
            snprintf(file[k], sizeof file[k], "%s", path);
        else if (sibling(path, ext[k], file[k], sizeof file[k]) < 0)
            return -1;
        if ((r = tex_out_open(&out[k], file[k])) == 0)
            opened++;
        else
            tex_out_close(&out[k], -1);
    }
    for (int k = 0; k < opened && r == 0; k++)
        r = write_channel(m, k, pic, out[k].fd, file[k]);
    for (int k = 0; k < opened; k++) /* all three kept, or none */
        r = tex_out_close(&out[k], r) < 0 ? -1 : r;
    return r;
}
