/* stream.c - OpenEXR encoding and decoding through the core C library
 *
 * The whole file lives in memory both ways: a pipe cannot seek, and the
 * core library writes the chunk offset table last.  One copy in memory
 * costs far less than the disk or pipe it crosses.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>

#include <omp.h>
#include <openexr.h>

#include "base/error.h"
#include "io/limit.h"
#include "io/planes.h"
#include "io/stream.h"

#define ATTR_SUBREGIONS "textura:subregions"
#define ATTR_HISTORY "textura:history"

int tex_buf_reserve(tex_buf *b, size_t cap)
{
    unsigned char *d;

    if (cap <= b->cap)
        return 0;
    if (cap < 2 * b->cap)
        cap = 2 * b->cap;
    if (!(d = b->mapped ? malloc(cap) : realloc(b->data, cap)))
        return tex_error("out of memory (%zu bytes)", cap);
    if (b->mapped) { /* pages do not grow: the bytes move to the heap */
        memcpy(d, b->data, b->len);
        tex_pages_free(b->data, b->mapped);
        b->mapped = 0;
    }
    b->data = d;
    b->cap = cap;
    return 0;
}

void tex_buf_free(tex_buf *b)
{
    if (b->mapped)
        tex_pages_free(b->data, b->mapped);
    else
        free(b->data);
    b->data = NULL;
    b->len = b->cap = b->mapped = 0;
}

/* The core library reports through a callback; keep its last word. */
static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    tex_error("%s", msg);
}

/* ---- writing ---- */

int tex_write_all(int fd, const void *p, size_t n, const char *name)
{
    const char *c = p;

    while (n > 0) {
        ssize_t w = write(fd, c, n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return tex_error("%s: write error: %s", name, strerror(errno));
        }
        c += w;
        n -= (size_t)w;
    }
    return 0;
}

/* Where encoded bytes go.  In memory (buf) they may land at any offset.  On
 * a file descriptor they must come in order: the header is buffered, then
 * written with a chunk offset table computed in advance, and the chunks pass
 * through buf (emptied), gathered into writes of up to STAGE bytes; a piece of half a
 * STAGE or more (a wide row's pixels, which the core hands over apart from the row's
 * header) leaves with what buf gathered in one writev, not copied to buf; the table the
 * core writes last must match ours.  STAGE is a pipe's default capacity: a larger stage
 * costs more first touches of pages than it saves in writes (doc/performance.md). */
#define STAGE (1 << 16)
struct wsink {
    tex_buf *buf;
    size_t base;
    int fd;              /* -1: memory only */
    const char *name;
    int streaming;       /* header sent: writes go to fd */
    uint64_t pos;        /* bytes sent to fd */
    uint64_t table_off;  /* where the offset table sits */
    unsigned char *table;
    size_t table_len;
    int seekable;        /* fd is a regular file: bytes land at their offsets (pwrite) */
};

/* The streamed bytes gathered in w's buf written out */
static int sink_flush(struct wsink *w)
{
    size_t n = w->streaming ? w->buf->len : 0;
    if (!n)
        return 0;
    w->buf->len = 0;
    return tex_write_all(w->fd, w->buf->data, n, w->name);
}

/* What w's buf gathered and then sz bytes at src, in one system call when the pipe takes
 * them whole: a row's pixels leave from where the core packed them, not copied to buf */
static int sink_write(struct wsink *w, const void *src, size_t sz)
{
    struct iovec v[2] = {{w->buf->data, w->buf->len}, {(void *)src, sz}};
    int k = w->buf->len ? 0 : 1;

    w->buf->len = 0;
    while (k < 2) {
        ssize_t n = writev(w->fd, v + k, 2 - k);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return tex_error("%s: write error: %s", w->name, strerror(errno));
        }
        for (; k < 2 && (size_t)n >= v[k].iov_len; k++)
            n -= (ssize_t)v[k].iov_len;
        if (k < 2)
            v[k].iov_base = (char *)v[k].iov_base + n, v[k].iov_len -= (size_t)n;
    }
    return 0;
}

static int64_t write_mem(exr_const_context_t ctxt, void *ud, const void *src, uint64_t sz,
                         uint64_t off, exr_stream_error_func_ptr_t ecb)
{
    struct wsink *w = ud;
    size_t end = w->base + off + sz;

    if (w->seekable) {
        const unsigned char *c = src;
        uint64_t done = 0;
        while (done < sz) {
            ssize_t k = pwrite(w->fd, c + done, sz - done, (off_t)(off + done));
            if (k < 0 && errno == EINTR)
                continue;
            if (k <= 0)
                return ecb(ctxt, EXR_ERR_WRITE_IO, "%s: write error: %s", w->name,
                           strerror(errno)), -1;
            done += (uint64_t)k;
        }
        return (int64_t)sz;
    }
    if (w->streaming) {
        if (off == w->pos) {
            if ((sz >= STAGE / 2 ? sink_write(w, src, sz)
                                 : (w->buf->len + sz > STAGE && sink_flush(w) < 0) ||
                                       tex_buf_reserve(w->buf, STAGE)) < 0)
                return ecb(ctxt, EXR_ERR_WRITE_IO, "%s", tex_errmsg()), -1;
            if (sz < STAGE / 2)
                memcpy(w->buf->data + w->buf->len, src, sz), w->buf->len += sz;
            w->pos += sz;
            return (int64_t)sz;
        }
        if (off == w->table_off && sz == w->table_len && memcmp(src, w->table, sz) == 0)
            return (int64_t)sz;
        return ecb(ctxt, EXR_ERR_WRITE_IO, "unexpected write at offset %llu of the stream",
                   (unsigned long long)off), -1;
    }
    if (tex_buf_reserve(w->buf, end) < 0)
        return ecb(ctxt, EXR_ERR_OUT_OF_MEMORY, "out of memory"), -1;
    memcpy(w->buf->data + w->base + off, src, sz);
    if (end > w->buf->len)
        w->buf->len = end;
    return (int64_t)sz;
}

/* Send the buffered header and the offset table of uncompressed scanline
 * chunks (each: int y, int size, then the pixels). */
static int start_streaming(struct wsink *w, const tex_map *m, int nchunks, int lines)
{
    uint64_t off;
    size_t row = (size_t)m->w * m->nc * 4;

    w->table_off = w->buf->len;
    w->table_len = (size_t)nchunks * 8;
    if (!(w->table = malloc(w->table_len)))
        return tex_error("out of memory");
    off = w->table_off + w->table_len;
    for (int k = 0; k < nchunks; k++) {
        int n = m->h - k * lines < lines ? m->h - k * lines : lines;
        memcpy(w->table + 8 * k, &off, 8); /* EXR is little-endian, as is this machine */
        off += 8 + n * row;
    }
    if (tex_write_all(w->fd, w->buf->data, w->buf->len, w->name) < 0 ||
        tex_write_all(w->fd, w->table, w->table_len, w->name) < 0)
        return -1;
    w->pos = w->table_off + w->table_len;
    w->streaming = 1;
    w->buf->len = 0; /* sent: buf gathers the chunks now */
    return 0;
}

/* A band of fill's rows from this size up in fresh pages (tex_pages_new): made once, its
 * first touch of 4 KiB pages is paid once (doc/performance.md) */
#define BAND_PAGES (256 << 10)

static const char *const chnames[4][4] = {
    {"Y"}, {"R", "G"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};

static int exr_fail(exr_context_t *ctx, exr_result_t rv, const char *what)
{
    if (rv != EXR_ERR_SUCCESS && strcmp(tex_errmsg(), "unknown error") == 0)
        tex_error("%s: %s", what, exr_get_default_error_message(rv));
    if (ctx && *ctx)
        exr_finish(ctx);
    return -1;
}

/* OpenEXR 3.1's ZIP compressor, when deflate does not shrink a chunk, stores its
 * predicted and interleaved bytes instead of the raw ones, which a reader takes for raw
 * pixels (a noise map of cells under 3 pixels wide came back as +-3e38 and NaN).  The
 * file format stores such a chunk raw: put the packed bytes back after it. */
static exr_result_t (*default_compress)(exr_encode_pipeline_t *);

static exr_result_t raw_if_incompressible(exr_encode_pipeline_t *enc)
{
    exr_result_t rv = __atomic_load_n(&default_compress, __ATOMIC_RELAXED)(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes >= enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer)
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    return rv;
}

/* Whether chunks are worth compressing.  Noise maps' float bits shrink little under ZIP,
 * for many times the CPU of writing them raw (doc/performance.md, io/ and cli/).
 * After four chunks in a row that shrink by less than an eighth, the next fifteen are
 * stored raw (a reader takes a chunk of its raw size as uncompressed, as the file format
 * has it), and every sixteenth is tried again. */
struct worth {
    int compressing; /* the part is compressed at all */
    int poor, skip;
};

/* Encode and write the chunk enc is set up for: compressed (raw_if_incompressible, in
 * place of the core library's compressor, kept in default_compress) or raw, as w says;
 * then w learns how well it shrank. */
static exr_result_t encode_chunk(exr_context_t ctx, int part, exr_encode_pipeline_t *enc,
                                 struct worth *w)
{
    if (enc->compress_fn && enc->compress_fn != raw_if_incompressible) /* the core's own */
        __atomic_store_n(&default_compress, enc->compress_fn, __ATOMIC_RELAXED);
    enc->compress_fn = w->compressing && !w->skip ? raw_if_incompressible : NULL;
    w->skip -= w->skip > 0;
    exr_result_t rv = exr_encoding_run(ctx, part, enc);
    if (rv || !enc->compress_fn)
        return rv;
    if (enc->compressed_bytes * 8 > enc->packed_bytes * 7)
        w->skip = ++w->poor >= 4 ? 15 : 0;
    else
        w->poor = 0;
    return rv;
}

/* One part for m: its storage, size and place, channels and attributes. */
static exr_result_t add_part(exr_context_t ctx, const tex_map *m, exr_storage_t st,
                             exr_compression_t comp, int *part)
{
    exr_result_t rv;

    if ((rv = exr_add_part(ctx, "", st, part)) ||
        (rv = exr_initialize_required_attr_simple(ctx, *part, m->w, m->h, comp)))
        return rv;
    /* deflate's level 4, as OpenEXR's own writers since 3.1.3 and OpenImageIO take it: about
     * twice level 6's speed for files a few percent larger (the core library keeps 6) */
    if (comp == EXR_COMPRESSION_ZIP && (rv = exr_set_zip_compression_level(ctx, *part, 4)))
        return rv;
    if (m->full_w > 0) { /* a window: the data window inside the full map's display window */
        exr_attr_box2i_t dw, disp;
        dw.min.x = m->x0;
        dw.min.y = m->y0;
        dw.max.x = m->x0 + m->w - 1;
        dw.max.y = m->y0 + m->h - 1;
        disp.min.x = disp.min.y = 0;
        disp.max.x = m->full_w - 1;
        disp.max.y = m->full_h - 1;
        if ((rv = exr_set_data_window(ctx, *part, &dw)) ||
            (rv = exr_set_display_window(ctx, *part, &disp)))
            return rv;
    }
    for (int ch = 0; ch < m->nc; ch++)
        if ((rv = exr_add_channel(ctx, *part, chnames[m->nc - 1][ch], EXR_PIXEL_FLOAT,
                                  EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1)))
            return rv;
    if (m->subregions > 0 && (rv = exr_attr_set_int(ctx, *part, ATTR_SUBREGIONS, m->subregions)))
        return rv;
    if (m->history && (rv = exr_attr_set_string(ctx, *part, ATTR_HISTORY, m->history)))
        return rv;
    return EXR_ERR_SUCCESS;
}

/* The first pixel's sample k of n channels (the channel whose samples are k of each pixel
 * in slot[k]) when they are float samples, neither subsampled nor skipped, of one map's
 * pixels n floats apart, its rows alike: the core's routines move these a sample at a
 * time, ours (pack_planes, unpack_planes) a line's runs at once.  0 when they are not. */
static int float_pixels(const exr_coding_channel_info_t *ch, int n, const uint8_t **first,
                        int slot[4])
{
    const uint8_t *lo = ch[0].encode_from_ptr;
    int seen = 0;
    if (n < 1 || n > 4)
        return 0;
    for (int c = 1; c < n; c++)
        if (ch[c].encode_from_ptr < lo)
            lo = ch[c].encode_from_ptr;
    for (int c = 0; c < n; c++) {
        const exr_coding_channel_info_t *x = &ch[c];
        long k = x->encode_from_ptr && lo ? (long)(x->encode_from_ptr - lo) : -1;
        if (x->data_type != EXR_PIXEL_FLOAT || x->user_data_type != EXR_PIXEL_FLOAT ||
            x->bytes_per_element != 4 || x->user_bytes_per_element != 4 ||
            x->x_samples != 1 || x->y_samples != 1 || x->user_pixel_stride != 4 * n ||
            x->user_line_stride != ch[0].user_line_stride || x->width != ch[0].width ||
            x->height != ch[0].height || k < 0 || k % 4 || k / 4 >= n || seen & 1 << k / 4)
            return 0;
        seen |= 1 << k / 4;
        slot[k / 4] = c;
    }
    *first = lo;
    return 1;
}

/* The core's pack for float_pixels' channels: each line's pixels split into the chunk's
 * channel runs (planes.h) */
static exr_result_t pack_planes(exr_encode_pipeline_t *enc)
{
    const exr_coding_channel_info_t *ch = enc->channels;
    const uint8_t *first;
    int slot[4], n = enc->channel_count, w = ch[0].width;
    float *dst = enc->packed_buffer, *plane[4];

    if (!float_pixels(ch, n, &first, slot))
        return EXR_ERR_INVALID_ARGUMENT;
    for (int y = 0; y < ch[0].height; y++, dst += (size_t)n * w) {
        for (int k = 0; k < n; k++)
            plane[k] = dst + (size_t)slot[k] * w;
        tex_planes_split(plane, (const float *)(first + (size_t)y * ch[0].user_line_stride), n,
                         (size_t)w);
    }
    enc->packed_bytes = (uint64_t)ch[0].height * n * w * 4;
    return EXR_ERR_SUCCESS;
}

/* The core's unpack for float_pixels' channels: each line's channel runs joined into its
 * pixels */
static exr_result_t unpack_planes(exr_decode_pipeline_t *dec)
{
    const exr_coding_channel_info_t *ch = dec->channels;
    const uint8_t *first;
    int slot[4], n = dec->channel_count, w = ch[0].width;
    const float *src = dec->unpacked_buffer, *plane[4];

    if (!float_pixels(ch, n, &first, slot))
        return EXR_ERR_INVALID_ARGUMENT;
    for (int y = 0; y < ch[0].height; y++, src += (size_t)n * w) {
        for (int k = 0; k < n; k++)
            plane[k] = src + (size_t)slot[k] * w;
        tex_planes_join((float *)(first + (size_t)y * ch[0].user_line_stride), plane, n,
                        (size_t)w);
    }
    return EXR_ERR_SUCCESS;
}

/* The core's default routines for enc, with pack_planes where its channels allow */
static exr_result_t choose_encoder(exr_context_t ctx, int part, exr_encode_pipeline_t *enc)
{
    const uint8_t *first;
    int slot[4];
    exr_result_t rv = exr_encoding_choose_default_routines(ctx, part, enc);
    if (!rv && float_pixels(enc->channels, enc->channel_count, &first, slot))
        enc->convert_and_pack_fn = pack_planes;
    return rv;
}

/* Point the encoder's channels (listed alphabetically: A B G R) at pixel p of
 * a map nc channels deep whose rows are w pixels apart. */
static void aim_encoder(exr_encode_pipeline_t *enc, const float *p, int w, int nc)
{
    for (int ch = 0; ch < enc->channel_count; ch++) {
        exr_coding_channel_info_t *cc = &enc->channels[ch];
        int k = 0;
        while (k < nc && strcmp(cc->channel_name, chnames[nc - 1][k]))
            k++;
        cc->user_bytes_per_element = 4;
        cc->user_data_type = EXR_PIXEL_FLOAT;
        cc->user_pixel_stride = 4 * nc;
        cc->user_line_stride = 4 * nc * w;
        cc->encode_from_ptr = (const uint8_t *)(p + k);
    }
}

/* Compressed scanline chunks go CHUNK_BATCH at a time (2 to 8 where a batch of 8 would pass
 * 32 MiB: a very wide map's): the chunks of a batch shared among the threads, each thread
 * packing and compressing its own in a pipeline of its own (the core library packs under
 * the context's lock and compresses outside it), their bytes kept, then the batch written
 * in order.  The batch is fixed by the map's width, not the thread count or the band, so the
 * file's bytes are the same for any -j.  Whether chunks are worth compressing (struct worth) is
 * decided a batch at a time: after a batch that shrank by less than an eighth, the next is
 * stored raw and the one after compresses only its first chunk (a probe: one chunk in
 * sixteen), until a probe shrinks by more. */
#define CHUNK_BATCH 8

struct slot { /* a chunk's bytes as the file stores them */
    uint8_t *data;
    size_t size, cap;
    exr_result_t rv;
    int compressed;
    uint64_t packed;
};

struct pipe {
    exr_encode_pipeline_t enc; /* first: stash_chunk finds its pipe from its pipeline */
    int ready;                 /* enc initialised, its routines chosen */
    struct slot *to;           /* where the chunk being made goes */
};

/* The pipeline's write routine: the chunk's bytes kept in its slot, written later in order */
static exr_result_t stash_chunk(exr_encode_pipeline_t *enc)
{
    struct slot *s = ((struct pipe *)enc)->to;
    size_t n = enc->compressed_bytes;
    if (n > s->cap) {
        uint8_t *d = realloc(s->data, n);
        if (!d)
            return EXR_ERR_OUT_OF_MEMORY;
        s->data = d, s->cap = n;
    }
    memcpy(s->data, enc->compressed_buffer, n);
    s->size = n;
    s->packed = enc->packed_bytes;
    return EXR_ERR_SUCCESS;
}

/* Chunk ci (its rows from row0, rows w pixels and nc channels wide) packed in pipe p,
 * compressed if compress says so, and kept in slot s */
static exr_result_t encode_slot(exr_context_t ctx, int part, struct pipe *p, struct slot *s,
                                const exr_chunk_info_t *ci, const float *row0, int w, int nc,
                                int compress)
{
    exr_result_t rv = p->ready ? exr_encoding_update(ctx, part, ci, &p->enc)
                               : exr_encoding_initialize(ctx, part, ci, &p->enc);
    if (rv)
        return rv;
    aim_encoder(&p->enc, row0, w, nc);
    if (!p->ready && (rv = choose_encoder(ctx, part, &p->enc)))
        return rv;
    p->ready = 1;
    if (p->enc.compress_fn && p->enc.compress_fn != raw_if_incompressible)
        __atomic_store_n(&default_compress, p->enc.compress_fn, __ATOMIC_RELAXED);
    p->enc.compress_fn = compress ? raw_if_incompressible : NULL;
    p->enc.yield_until_ready_fn = NULL;
    p->enc.write_fn = stash_chunk;
    p->to = s;
    s->compressed = compress;
    return exr_encoding_run(ctx, part, &p->enc);
}

/* The n chunks of the batch whose first row is y (of the part; rows from row0) made at
 * once, a pipe per thread, and written in order; w learns how well they shrank */
static exr_result_t encode_batch(exr_context_t ctx, int part, struct pipe *pipes, int npipes,
                                 struct slot *slots, int n, int y, int lines, const float *row0,
                                 const tex_map *m, struct worth *w)
{
    exr_chunk_info_t ci[CHUNK_BATCH];
    exr_result_t rv = EXR_ERR_SUCCESS;
    size_t row = (size_t)m->w * m->nc;
    int all = !w->poor, probe = w->poor && !w->skip;
    for (int i = 0; i < n && !rv; i++)
        rv = exr_write_scanline_chunk_info(ctx, part, y + i * lines, &ci[i]);
    if (rv)
        return rv;
    int nt = npipes < n ? npipes : n;
#pragma omp parallel num_threads(nt) if (nt > 1)
    {
        int t = omp_get_thread_num(), step = omp_get_num_threads();
        for (int i = t; i < n; i += step)
            slots[i].rv = encode_slot(ctx, part, &pipes[t], &slots[i], &ci[i],
                                      row0 + (size_t)i * lines * row, m->w, m->nc,
                                      w->compressing && (all || (probe && i == 0)));
    }
    uint64_t packed = 0, stored = 0;
    for (int i = 0; i < n; i++) {
        if ((rv = slots[i].rv) ||
            (rv = exr_write_scanline_chunk(ctx, part, ci[i].start_y, slots[i].data,
                                           slots[i].size)))
            return rv;
        if (slots[i].compressed)
            packed += slots[i].packed, stored += slots[i].size;
    }
    if (packed)
        w->poor = w->skip = stored * 8 > packed * 7;
    else
        w->skip = 0; /* a raw batch: the next one probes */
    return EXR_ERR_SUCCESS;
}

static void writer_init(exr_context_initializer_t *init, struct wsink *sink)
{
    init->user_data = sink;
    init->write_fn = write_mem;
    init->error_handler_fn = on_exr_error;
    init->max_image_width = TEX_MAP_MAX_SIDE;
    init->max_image_height = TEX_MAP_MAX_SIDE;
}

static const exr_compression_t ctype[] = {EXR_COMPRESSION_NONE, EXR_COMPRESSION_ZIP,
                                          EXR_COMPRESSION_PIZ};

/* A compressed part's chunks, a batch at a time (encode_batch): from m's rows, or from
 * fill's, made a batch at a time into band (brows rows); -1 with the error set. */
static int encode_batches(exr_context_t ctx, int part, const tex_map *m, tex_rows_fn fill,
                          void *arg, float *band, int brows, int lines, struct wsink *sink,
                          struct worth *w)
{
    struct slot slots[CHUNK_BATCH];
    struct pipe pipes[CHUNK_BATCH];
    exr_result_t rv = EXR_ERR_SUCCESS;
    int r = 0, y0 = m->full_w > 0 ? m->y0 : 0, npipes = omp_get_max_threads();
    npipes = npipes < CHUNK_BATCH ? npipes : CHUNK_BATCH;
    memset(slots, 0, sizeof slots);
    memset(pipes, 0, sizeof pipes);
    for (int y = 0; y < m->h && !r && !rv; y += brows) {
        int rows = m->h - y < brows ? m->h - y : brows;
        /* a batch's rows reach a reader before the next batch is made */
        if (band && (sink_flush(sink) < 0 || fill(arg, y, rows, band) < 0))
            r = -1;
        else
            rv = encode_batch(ctx, part, pipes, npipes, slots, (rows + lines - 1) / lines,
                              y + y0, lines, band ? band : tex_map_row(m, y), m, w);
    }
    for (int i = 0; i < CHUNK_BATCH; i++) {
        if (pipes[i].ready)
            exr_encoding_destroy(ctx, &pipes[i].enc);
        free(slots[i].data);
    }
    if (rv)
        return exr_fail(NULL, rv, "EXR encode");
    return r;
}

/* An uncompressed part's chunks one after the other (the stream's case): from m's rows, or
 * from at's where they lie, or from fill's, made brows at a time into band; -1 with the
 * error set, ctx the caller's */
static int encode_raw(exr_context_t ctx, int part, const tex_map *m, tex_rows_fn fill,
                      tex_rows_at_fn at, void *arg, float *band, int brows, int lines,
                      struct wsink *sink, struct worth *w)
{
    exr_encode_pipeline_t enc;
    exr_chunk_info_t ci;
    exr_result_t rv = EXR_ERR_SUCCESS;
    const float *lie = NULL; /* at's rows, from row ly to row lend */
    int r = 0, ly = 0, lend = 0;
    size_t row = (size_t)m->w * m->nc;

    memset(&enc, 0, sizeof enc);
    for (int y = 0; y < m->h && !r && !rv; y += lines) {
        const float *row0 = at     ? NULL
                            : band ? band + (size_t)(y % brows) * row
                                   : tex_map_row(m, y);
        int left = m->h - y < brows - y % brows ? m->h - y : brows - y % brows;
        /* a band's rows reach a reader before the next band is made */
        if ((band || at) && y % brows == 0 && sink_flush(sink) < 0) {
            r = -1;
            break;
        }
        if (at && y >= lend) {
            int k = at(arg, y, left, &lie);
            if (k < 1) {
                r = -1;
                break;
            }
            ly = y, lend = y + k;
        }
        if (at)
            row0 = lie + (size_t)(y - ly) * row;
        else if (band && y % brows == 0 && fill(arg, y, left, band) < 0) {
            r = -1;
            break;
        }
        if ((rv = exr_write_scanline_chunk_info(ctx, part, y + (m->full_w > 0 ? m->y0 : 0), &ci)) ||
            (rv = y == 0 ? exr_encoding_initialize(ctx, part, &ci, &enc)
                         : exr_encoding_update(ctx, part, &ci, &enc)))
            break;
        aim_encoder(&enc, row0, m->w, m->nc);
        if (y == 0 && (rv = choose_encoder(ctx, part, &enc)))
            break;
        rv = encode_chunk(ctx, part, &enc, w);
    }
    exr_encoding_destroy(ctx, &enc);
    if (rv)
        return exr_fail(NULL, rv, "EXR encode");
    return r;
}

static int encode(const tex_map *m, tex_rows_fn fill, tex_rows_at_fn at, void *arg,
                  enum tex_compression c, struct wsink *sink)
{
    float *band = NULL; /* fill's rows, a band of chunks at a time */
    size_t band_mapped = 0;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    exr_result_t rv;
    tex_buf *out = sink->buf;
    int part, lines, nchunks;
    struct worth worth = {c != TEX_COMPRESS_NONE, 0, 0};
    size_t est = (size_t)m->w * m->h * m->nc * 4 + 4096 + (size_t)m->h * 16;

    if (sink->fd < 0 && !fill && c == TEX_COMPRESS_NONE &&
        tex_buf_reserve(out, out->len + est) < 0)
        return -1;
    writer_init(&init, sink);
    if ((rv = exr_start_write(&ctx, "stream", EXR_WRITE_FILE_DIRECTLY, &init)))
        return exr_fail(&ctx, rv, "EXR write");
    if ((rv = add_part(ctx, m, EXR_STORAGE_SCANLINE, ctype[c], &part)) ||
        (rv = exr_write_header(ctx)) || (rv = exr_get_scanlines_per_chunk(ctx, part, &lines)) ||
        (rv = exr_get_chunk_count(ctx, part, &nchunks)))
        return exr_fail(&ctx, rv, "EXR header");
    if (sink->fd >= 0 && !sink->seekable && start_streaming(sink, m, nchunks, lines) < 0) {
        exr_finish(&ctx);
        return -1;
    }
    /* fill makes whole chunks, 64 rows at a time (fewer where they pass 8 MiB): its work per
     * call (a parallel loop, say) then outweighs starting it; compressed, a batch of them
     * (fewer than CHUNK_BATCH, 2 at least, where they pass 32 MiB: a 65536-wide map's) */
    size_t row = (size_t)m->w * m->nc * sizeof(float), fit = ((size_t)8 << 20) / row;
    size_t chunks = ((size_t)32 << 20) / (row * (size_t)lines);
    int want = fit < 64 ? (fit ? (int)fit : 1) : 64;
    int batch = chunks < CHUNK_BATCH ? (chunks < 2 ? 2 : (int)chunks) : CHUNK_BATCH;
    int brows = c != TEX_COMPRESS_NONE ? lines * batch : lines * ((want + lines - 1) / lines);
    if (lines != 1)
        at = NULL; /* at's rows are whole chunks only a line high */
    if (fill && !at &&
        !(band = tex_pages_new(sizeof *band * (size_t)brows * m->w * m->nc, BAND_PAGES,
                               &band_mapped))) {
        exr_finish(&ctx);
        return tex_error("out of memory");
    }
    if (band) /* its pages made here, not in fill's inner loop */
        tex_pages_touch(band, band_mapped);
    int r = c != TEX_COMPRESS_NONE
                ? encode_batches(ctx, part, m, fill, arg, band, brows, lines, sink, &worth)
                : encode_raw(ctx, part, m, fill, at, arg, band, brows, lines, sink, &worth);
    tex_pages_free(band, band_mapped);
    if (r < 0) {
        exr_finish(&ctx);
        return -1;
    }
    if ((rv = exr_finish(&ctx)))
        return exr_fail(NULL, rv, "EXR finish");
    return sink_flush(sink);
}

/* Tile tx, ty of level l (the map lv) encoded and written, its pixels from px (a band of
 * rows, lv's width) or, with px NULL, from lv; enc is destroyed after a written tile. */
static exr_result_t write_tile(exr_context_t ctx, int part, exr_encode_pipeline_t *enc,
                               const tex_map *lv, int l, int tx, int ty, int tile,
                               const float *px, struct worth *worth)
{
    exr_chunk_info_t ci;
    exr_result_t rv;

    if ((rv = exr_write_tile_chunk_info(ctx, part, tx, ty, l, l, &ci)))
        return rv;
    /* OpenEXR 3.1 sizes edge tiles of every level by the full-resolution
     * level's edges: give the tile its own level's size. */
    ci.width = lv->w - tx * tile < tile ? lv->w - tx * tile : tile;
    ci.height = lv->h - ty * tile < tile ? lv->h - ty * tile : tile;
    ci.unpacked_size = (uint64_t)ci.width * ci.height * lv->nc * 4;
    if ((rv = exr_encoding_initialize(ctx, part, &ci, enc)))
        return rv;
    aim_encoder(enc, px ? px : tex_map_px(lv, tx * tile, ty * tile), lv->w, lv->nc);
    if ((rv = choose_encoder(ctx, part, enc)) ||
        (rv = encode_chunk(ctx, part, enc, worth)))
        return rv;
    exr_encoding_destroy(ctx, enc);
    return EXR_ERR_SUCCESS;
}

/* m tiled (with its mip levels), or, with fill, the map head describes made
 * a band of tile rows at a time (one level). */
static int encode_tiled(const tex_map *m, tex_rows_fn fill, void *arg, int tile, int mipmap,
                        enum tex_compression c, struct wsink *sink)
{
    float *band = NULL;
    size_t band_mapped = 0;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc;
    exr_result_t rv = EXR_ERR_SUCCESS;
    tex_map *lv[32] = {(tex_map *)m};
    int part, n = 1, r = -1;
    struct worth worth = {c != TEX_COMPRESS_NONE, 0, 0};
    int32_t nx, ny;

    if (mipmap && m->subregions > 0)
        return tex_usage_error("--mipmap: a map of subregion ids cannot be averaged into levels");
    for (; mipmap && (lv[n - 1]->w > 1 || lv[n - 1]->h > 1); n++)
        if (!(lv[n] = tex_map_reduce(lv[n - 1])))
            goto done;
    if (fill && !(band = tex_pages_new(sizeof *band * (size_t)tile * m->w * m->nc, BAND_PAGES,
                                       &band_mapped))) {
        tex_error("out of memory");
        goto done;
    }
    if (band)
        tex_pages_touch(band, band_mapped);
    memset(&enc, 0, sizeof enc);
    writer_init(&init, sink);
    if ((rv = exr_start_write(&ctx, "stream", EXR_WRITE_FILE_DIRECTLY, &init)) ||
        (rv = add_part(ctx, m, EXR_STORAGE_TILED, ctype[c], &part)) ||
        (rv = exr_set_tile_descriptor(ctx, part, (uint32_t)tile, (uint32_t)tile,
                                      mipmap ? EXR_TILE_MIPMAP_LEVELS : EXR_TILE_ONE_LEVEL,
                                      EXR_TILE_ROUND_DOWN)) ||
        (rv = exr_write_header(ctx)) || (rv = exr_get_tile_levels(ctx, part, &nx, &ny)))
        goto done;
    if (nx != n || ny != n) {
        tex_error("EXR levels: %d from the core library, %d made", nx, n);
        goto done;
    }
    /* A pipeline per tile: one reused across levels of other sizes wrote
     * corrupt ZIP chunks below the top level (OpenEXR 3.1). */
    for (int l = 0; l < n; l++)
        for (int ty = 0; ty * tile < lv[l]->h; ty++) {
            if (band && fill(arg, ty * tile, m->h - ty * tile < tile ? m->h - ty * tile : tile,
                             band) < 0)
                goto done;
            for (int tx = 0; tx * tile < lv[l]->w; tx++)
                if ((rv = write_tile(ctx, part, &enc, lv[l], l, tx, ty, tile,
                                     band ? band + (size_t)tx * tile * m->nc : NULL, &worth)))
                    goto done;
        }
    exr_encoding_destroy(ctx, &enc);
    rv = exr_finish(&ctx);
    r = rv ? -1 : 0;
done:
    if (ctx) {
        exr_encoding_destroy(ctx, &enc);
        exr_finish(&ctx);
    }
    if (r < 0 && rv != EXR_ERR_SUCCESS)
        exr_fail(NULL, rv, "EXR tiled write");
    for (int l = 1; l < n; l++)
        tex_map_free(lv[l]);
    tex_pages_free(band, band_mapped);
    return r;
}

int tex_exr_encode_tiled(const tex_map *m, int tile, int mipmap, enum tex_compression c,
                         tex_buf *out)
{
    struct wsink sink = {out, out->len, -1, "memory", 0, 0, 0, NULL, 0, 0};
    return encode_tiled(m, NULL, NULL, tile, mipmap, c, &sink);
}

int tex_exr_encode(const tex_map *m, enum tex_compression c, tex_buf *out)
{
    struct wsink sink = {out, out->len, -1, "memory", 0, 0, 0, NULL, 0, 0};
    return encode(m, NULL, NULL, NULL, c, &sink);
}

/* A pipe's default 64 KiB buffer costs a context switch per 64 KiB; ask for
 * more (Linux grants up to /proc/sys/fs/pipe-max-size, 1 MiB by default). */
void tex_pipe_widen(int fd)
{
#ifdef F_SETPIPE_SZ
    struct stat st;
    if (fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode) && fcntl(fd, F_GETPIPE_SZ) < (1 << 20))
        (void)fcntl(fd, F_SETPIPE_SZ, 1 << 20);
#else
    (void)fd;
#endif
}

int tex_exr_write_fd(const tex_map *m, int fd, const char *name)
{
    tex_buf head = {0};
    struct wsink sink = {&head, 0, fd, name, 0, 0, 0, NULL, 0, 0};
    int r;

    tex_pipe_widen(fd);
    r = encode(m, NULL, NULL, NULL, TEX_COMPRESS_NONE, &sink);

    free(sink.table);
    tex_buf_free(&head);
    return r;
}

int tex_exr_write_rows(const tex_map *head, tex_rows_fn fill, void *arg, int tile,
                       enum tex_compression c, int fd, const char *name)
{
    return tex_exr_write_rows_at(head, fill, NULL, arg, tile, c, fd, name);
}

int tex_exr_write_rows_at(const tex_map *head, tex_rows_fn fill, tex_rows_at_fn at, void *arg,
                          int tile, enum tex_compression c, int fd, const char *name)
{
    tex_buf hb = {0};
    struct stat st;
    struct wsink sink = {&hb, 0, fd, name, 0, 0, 0, NULL, 0, 0};
    int r;

    sink.seekable = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && lseek(fd, 0, SEEK_CUR) == 0;
    if (!sink.seekable && tile > 0)
        return tex_usage_error("%s: tiles are written to a file, not a pipe", name);
    if (!sink.seekable) {
        tex_pipe_widen(fd);
        c = TEX_COMPRESS_NONE; /* a pipe carries the stream, never compressed */
    }
    r = tile > 0 ? encode_tiled(head, fill, arg, tile, 0, c, &sink)
                 : encode(head, fill, c == TEX_COMPRESS_NONE ? at : NULL, arg, c, &sink);
    free(sink.table);
    tex_buf_free(&hb);
    return r;
}

/* ---- reading ---- */

struct rsrc {
    const unsigned char *data;
    size_t len;
};

/* Set when a read of the data came back short: the chunk that then fails lies past the end
 * of the data, and the message says "truncated" as PNG, PNM and PFM do (the core says only
 * that a chunk's leader is corrupt).  Cleared once the header is read, whose parse may
 * read past the end of a small file. */
static _Thread_local int exr_ran_short;

static int64_t read_mem(exr_const_context_t ctxt, void *ud, void *dst, uint64_t sz, uint64_t off,
                        exr_stream_error_func_ptr_t ecb)
{
    struct rsrc *r = ud;

    (void)ctxt;
    (void)ecb;
    if (off >= r->len || sz > r->len - off)
        exr_ran_short = 1;
    if (off >= r->len)
        return 0;
    if (sz > r->len - off)
        sz = r->len - off;
    memcpy(dst, r->data + off, sz);
    return (int64_t)sz;
}

static int64_t size_mem(exr_const_context_t ctxt, void *ud)
{
    (void)ctxt;
    return (int64_t)((struct rsrc *)ud)->len;
}

/* A pipe read as it is decoded.  The core reads the header, the offset
 * table and then the chunks we ask for in increasing order, so only a
 * window of the stream need be kept: bytes before the latest request go. */
struct rstream {
    int fd;
    const char *name;
    unsigned char *buf;
    size_t cap, len;
    uint64_t base; /* stream offset of buf[0] */
    int eof;
    size_t max;    /* the input limit (io/limit.h) on the bytes read, base + len */
    int over;      /* the stream passed it */
};

/* A pipe's window of 1 MiB holding prefix_len bytes read before; -1 with the error set
 * (the limit's variable malformed, or no memory). */
static int rstream_open(struct rstream *r, int fd, const char *name, const void *prefix,
                        size_t prefix_len)
{
    *r = (struct rstream){fd, name, NULL, 1 << 20, prefix_len, 0, 0, 0, 0};
    if (tex_input_max(&r->max) < 0)
        return -1;
    if (prefix_len > r->cap || !(r->buf = malloc(r->cap)))
        return tex_error("out of memory");
    if (prefix_len) /* prefix may be NULL then */
        memcpy(r->buf, prefix, prefix_len);
    tex_pipe_widen(fd);
    return 0;
}

/* The limit's word when the stream passed it: the decoder's own word on the read that
 * failed would hide it.  Without the input's name, which callers add. */
static void rstream_limit_word(const struct rstream *r)
{
    if (r->over)
        tex_error("over the input limit of %zu bytes (TEXTURA_MAX_INPUT)", r->max);
}

/* One read of at most want bytes after the window's, none beyond a byte past the limit: its
 * count (0 at the end, eof set), or -1 with errno */
static ssize_t rstream_read(struct rstream *r, size_t want)
{
    size_t left = (size_t)(r->max + 1 - r->base - r->len);
    ssize_t k;
    do
        k = read(r->fd, r->buf + r->len, want < left ? want : left);
    while (k < 0 && errno == EINTR);
    if (k == 0)
        r->eof = 1;
    return k;
}

static int64_t read_stream(exr_const_context_t ctxt, void *ud, void *dst, uint64_t sz,
                           uint64_t off, exr_stream_error_func_ptr_t ecb)
{
    struct rstream *r = ud;
    size_t drop, need, avail;

    if (off < r->base)
        return ecb(ctxt, EXR_ERR_READ_IO, "the stream's chunks are out of order"), -1;
    /* Bytes between the window and the request are read and dropped, never kept: a gap in
     * the offsets is bounded by the limit, and the window by the largest request. */
    while (off > r->base + r->len && !r->eof && r->base + r->len <= r->max) {
        r->base += r->len;
        r->len = 0;
        size_t gap = (size_t)(off - r->base);
        ssize_t k = rstream_read(r, gap < r->cap ? gap : r->cap);
        if (k < 0)
            return ecb(ctxt, EXR_ERR_READ_IO, "%s: %s", r->name, strerror(errno)), -1;
        r->len = (size_t)k;
    }
    if (off > r->base + r->len) { /* the stream ended, or passed the limit, before it */
        r->over = r->base + r->len > r->max;
        exr_ran_short = 1;
        return r->over ? ecb(ctxt, EXR_ERR_READ_IO, "over the input limit"), -1 : 0;
    }
    need = (size_t)(off + sz - r->base);
    if (need > r->cap) {
        /* Out of room: drop what lies before this request, then grow if still short. */
        drop = off - r->base < r->len ? (size_t)(off - r->base) : r->len;
        memmove(r->buf, r->buf + drop, r->len - drop);
        r->base += drop;
        r->len -= drop;
        need = (size_t)(off + sz - r->base);
    }
    if (need > r->cap) {
        size_t cap = need > (1 << 20) ? need : (1 << 20);
        unsigned char *b = realloc(r->buf, cap);
        if (!b)
            return ecb(ctxt, EXR_ERR_OUT_OF_MEMORY, "out of memory"), -1;
        r->buf = b;
        r->cap = cap;
    }
    /* Bytes past the limit are refused as the whole-map readers refuse them, once a
     * request reaches them (the header's is 4 KiB, its declared size judged first);
     * reads stop a byte past it. */
    while (r->len < need && !r->eof && r->base + r->len <= r->max) {
        ssize_t k = rstream_read(r, r->cap - r->len);
        if (k < 0)
            return ecb(ctxt, EXR_ERR_READ_IO, "%s: %s", r->name, strerror(errno)), -1;
        r->len += (size_t)k;
    }
    if (r->base + r->len > r->max && off + sz > r->max) {
        r->over = 1;
        return ecb(ctxt, EXR_ERR_READ_IO, "over the input limit"), -1;
    }
    avail = r->base + r->len > off ? (size_t)(r->base + r->len - off) : 0;
    if (avail > sz)
        avail = (size_t)sz;
    exr_ran_short |= avail < sz;
    memcpy(dst, r->buf + (off - r->base), avail);
    return (int64_t)avail;
}

static int64_t size_unknown(exr_const_context_t ctxt, void *ud)
{
    (void)ctxt;
    (void)ud;
    return -1;
}

/* Order the file's channels into the map's: R G B A, Y A, or as listed. */
static int order_channels(const exr_attr_chlist_t *cl, int map[4])
{
    static const char *const pref[][4] = {{"R", "G", "B", "A"}, {"Y", "A"}};
    int n = cl->num_channels < 4 ? cl->num_channels : 4;

    for (int p = 0; p < 2; p++) {
        int found = 0;
        for (int k = 0; k < 4 && pref[p][k]; k++)
            for (int i = 0; i < cl->num_channels; i++)
                if (strcmp(cl->entries[i].name.str, pref[p][k]) == 0)
                    map[found++] = i;
        if (found > 0 && (found == cl->num_channels || found >= 3)) {
            return found;
        }
    }
    for (int i = 0; i < n; i++)
        map[i] = i;
    return n;
}

static tex_map *decode(exr_context_initializer_t *init, const char *name, tex_map ***levels,
                       int *nlevels);

tex_map *tex_exr_decode(const void *data, size_t len, const char *name)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    struct rsrc src = {data, len};

    init.user_data = &src;
    init.read_fn = read_mem;
    init.size_fn = size_unknown; /* a chunk past the end is then read short: "truncated" */
    return decode(&init, name, NULL, NULL);
}

tex_map **tex_exr_decode_levels(const void *data, size_t len, const char *name, int *n)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    struct rsrc src = {data, len};
    tex_map **lv = NULL;

    init.user_data = &src;
    init.read_fn = read_mem;
    init.size_fn = size_unknown; /* as tex_exr_decode */
    *n = 0;
    tex_map *m = decode(&init, name, &lv, n);
    if (m && !lv) { /* scanline: one level */
        if (!(lv = malloc(sizeof *lv))) {
            tex_map_free(m);
            tex_error("out of memory");
            return NULL;
        }
        lv[0] = m;
        *n = 1;
    }
    return m ? lv : NULL;
}

tex_map *tex_exr_read_fd(int fd, const void *prefix, size_t prefix_len, const char *name)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    struct rstream r;
    tex_map *m = NULL;

    if (rstream_open(&r, fd, name, prefix, prefix_len) < 0) {
        free(r.buf);
        return NULL;
    }
    init.user_data = &r;
    init.read_fn = read_stream;
    init.size_fn = size_unknown;
    if (!(m = decode(&init, name, NULL, NULL)))
        rstream_limit_word(&r);
    free(r.buf);
    return m;
}

/* The compressions this system's core library cannot decode (OpenEXR 3.1
 * has no DWA in C): the name, or NULL. */
static const char *undecodable(exr_compression_t c)
{
    return c == EXR_COMPRESSION_DWAA ? "DWAA" : c == EXR_COMPRESSION_DWAB ? "DWAB" : NULL;
}

const char *tex_exr_unsupported(const void *data, size_t len)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    struct rsrc src = {data, len};
    exr_context_t ctx = NULL;
    exr_compression_t c = EXR_COMPRESSION_NONE;

    init.user_data = &src;
    init.read_fn = read_mem;
    init.size_fn = size_mem;
    init.error_handler_fn = NULL;
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE;
    if (exr_start_read(&ctx, "probe", &init) == EXR_ERR_SUCCESS)
        exr_get_compression(ctx, 0, &c);
    if (ctx)
        exr_finish(&ctx);
    return undecodable(c);
}

/* The first part's layout: scanline or tiled storage (*lines 0: tiled),
 * the data window, full-resolution channels.  0, or -1 with the error set. */
static int decode_header(exr_context_t ctx, exr_attr_box2i_t *dw, const exr_attr_chlist_t **cl,
                         int *lines)
{
    exr_storage_t st;
    exr_compression_t comp;
    exr_result_t rv;
    int nparts;
    if ((rv = exr_get_count(ctx, &nparts)) || nparts < 1 || (rv = exr_get_storage(ctx, 0, &st)) ||
        (rv = exr_get_compression(ctx, 0, &comp)))
        return tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
    if (st != EXR_STORAGE_SCANLINE && st != EXR_STORAGE_TILED)
        return tex_error("deep OpenEXR data is not a texture map");
    if (undecodable(comp))
        return tex_error("unsupported compression %s", undecodable(comp));
    *lines = 0;
    if ((rv = exr_get_data_window(ctx, 0, dw)) || (rv = exr_get_channels(ctx, 0, cl)) ||
        (st == EXR_STORAGE_SCANLINE && (rv = exr_get_scanlines_per_chunk(ctx, 0, lines))))
        return tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
    if ((*cl)->num_channels < 1)
        return tex_error("OpenEXR file has no channels");
    for (int i = 0; i < (*cl)->num_channels; i++)
        if ((*cl)->entries[i].x_sampling != 1 || (*cl)->entries[i].y_sampling != 1)
            return tex_error("subsampled OpenEXR channels are not supported");
    return 0;
}

/* Point the decoder's channels at m's pixel (x, y): channel order[k] into
 * sample k, the others skipped. */
static void aim_channels(exr_decode_pipeline_t *dec, const int *order, tex_map *m, int x, int y)
{
    int nc = m->nc;
    for (int i = 0; i < dec->channel_count; i++) {
        exr_coding_channel_info_t *cc = &dec->channels[i];
        int k = -1;
        for (int j = 0; j < nc; j++)
            if (order[j] == i)
                k = j;
        if (k < 0) {
            cc->decode_to_ptr = NULL; /* skipped channel */
            continue;
        }
        cc->user_bytes_per_element = 4;
        cc->user_data_type = EXR_PIXEL_FLOAT;
        cc->user_pixel_stride = 4 * nc;
        cc->user_line_stride = 4 * nc * m->w;
        cc->decode_to_ptr = (uint8_t *)(tex_map_px(m, x, y) + k);
    }
}

/* The error of the chunk at scanline or tile row y that could not be read (rv: the core's
 * code, 0 when decoding failed): truncated where the data ran short, else corrupt. */
static int chunk_error(exr_result_t rv, const char *where, int y)
{
    if (exr_ran_short)
        return tex_error("truncated OpenEXR data at %s %d", where, y);
    if (rv)
        return tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
    return tex_error("truncated or corrupt OpenEXR data at %s %d", where, y);
}

/* Decode one chunk whose info is ci into m at (x, y); first: the pipeline is new. */
static int decode_one(exr_context_t ctx, exr_decode_pipeline_t *dec, exr_chunk_info_t *ci,
                      int first, const int *order, tex_map *m, int x, int y)
{
    exr_result_t rv = first ? exr_decoding_initialize(ctx, 0, ci, dec)
                            : exr_decoding_update(ctx, 0, ci, dec);
    if (rv)
        return tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
    aim_channels(dec, order, m, x, y);
    if (first && (rv = exr_decoding_choose_default_routines(ctx, 0, dec)))
        return tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
    const uint8_t *at;
    int slot[4];
    /* (a channel alone, uncompressed, the core reads where it goes, with no unpack) */
    if (first && dec->unpack_and_convert_fn &&
        float_pixels(dec->channels, dec->channel_count, &at, slot))
        dec->unpack_and_convert_fn = unpack_planes;
    /* A chunk read short decodes (the core, not told the data's size, fills the rest): the
     * data ended in it.  (Returning -1 from the read instead overran the core's buffer.) */
    exr_ran_short = 0; /* the header's parse, or another reader's, may have read short */
    if (exr_decoding_run(ctx, 0, dec) || exr_ran_short)
        return chunk_error(0, ci->type == EXR_STORAGE_TILED ? "tile row" : "scanline", y);
    return 0;
}

/* Every chunk of the first part's level l (tiled; 0 is the full resolution) into m. */
static int decode_chunks(exr_context_t ctx, exr_decode_pipeline_t *dec, exr_attr_box2i_t dw,
                         int lines, const int *order, tex_map *m, int l)
{
    exr_chunk_info_t ci;
    exr_result_t rv;
    int32_t tw, th;

    if (lines > 0) {
        for (int y = dw.min.y; y <= dw.max.y; y += lines)
            if ((rv = exr_read_scanline_chunk_info(ctx, 0, y, &ci)) ||
                decode_one(ctx, dec, &ci, y == dw.min.y, order, m, 0, y - dw.min.y) < 0)
                return rv ? chunk_error(rv, "scanline", y - dw.min.y) : -1;
        return 0;
    }
    if ((rv = exr_get_tile_sizes(ctx, 0, l, l, &tw, &th)) || tw < 1 || th < 1)
        return tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
    for (int ty = 0; ty * (int64_t)th < m->h; ty++)
        for (int tx = 0; tx * (int64_t)tw < m->w; tx++)
            if ((rv = exr_read_tile_chunk_info(ctx, 0, tx, ty, l, l, &ci)) ||
                decode_one(ctx, dec, &ci, l == 0 && tx == 0 && ty == 0, order, m, tx * tw,
                           ty * th) < 0)
                return rv ? chunk_error(rv, "tile row", ty * th) : -1;
    return 0;
}

/* The mip levels 1.. of a tiled, mip-mapped first part into (*levels)[1..]:
 * (*levels)[0] is m.  Levels come only from square-rounded-down mip-maps of
 * one level per halving (OpenEXR's MIPMAP_LEVELS, ROUND_DOWN). */
static int decode_levels(exr_context_t ctx, exr_decode_pipeline_t *dec, exr_attr_box2i_t dw,
                         const int *order, tex_map *m, tex_map ***levels, int *nlevels)
{
    exr_tile_level_mode_t mode;
    exr_tile_round_mode_t round;
    uint32_t tx, ty;
    int32_t nx, ny;
    tex_map **lv;

    *nlevels = 1;
    if (!(*levels = lv = calloc(1, sizeof *lv)))
        return tex_error("out of memory");
    lv[0] = m;
    if (exr_get_tile_descriptor(ctx, 0, &tx, &ty, &mode, &round) != EXR_ERR_SUCCESS ||
        mode != EXR_TILE_MIPMAP_LEVELS || round != EXR_TILE_ROUND_DOWN ||
        exr_get_tile_levels(ctx, 0, &nx, &ny) != EXR_ERR_SUCCESS || nx < 2 || nx > 32)
        return 0;
    if (!(lv = realloc(lv, (size_t)nx * sizeof *lv)))
        return tex_error("out of memory");
    *levels = lv;
    for (int l = 1; l < nx; l++) {
        int32_t w, h;
        if (exr_get_level_sizes(ctx, 0, l, l, &w, &h) != EXR_ERR_SUCCESS)
            return tex_error("corrupt OpenEXR stream (mip level %d)", l);
        if (!(lv[l] = tex_map_new(w, h, m->nc)))
            return -1;
        *nlevels = l + 1;
        if (decode_chunks(ctx, dec, dw, 0, order, lv[l], l) < 0)
            return -1;
    }
    return 0;
}

/* What the header says of map m beyond its pixels (m's nc channels, order[] of cl's, data
 * window dw): a warning naming the channels kept where there were more, its subregions,
 * its history, and its place where it is a window of a larger map (the display window). */
static int header_attrs(exr_context_t ctx, const exr_attr_chlist_t *cl, const int *order,
                        exr_attr_box2i_t dw, const char *name, tex_map *m)
{
    exr_attr_box2i_t disp;
    int32_t sub, hlen;
    const char *hist;

    if (cl->num_channels > m->nc) {
        char kept[64] = "";
        for (int k = 0; k < m->nc; k++)
            snprintf(kept + strlen(kept), sizeof kept - strlen(kept), " %.8s",
                     cl->entries[order[k]].name.str);
        tex_warning("%s: %d channels, kept%s", name, cl->num_channels, kept);
    }
    if (exr_attr_get_int(ctx, 0, ATTR_SUBREGIONS, &sub) == EXR_ERR_SUCCESS && sub > 0)
        m->subregions = sub;
    if (exr_attr_get_string(ctx, 0, ATTR_HISTORY, &hlen, &hist) == EXR_ERR_SUCCESS && hist) {
        if (!(m->history = malloc((size_t)hlen + 1)))
            return tex_error("out of memory");
        memcpy(m->history, hist, (size_t)hlen);
        m->history[hlen] = '\0';
    }
    if (exr_get_display_window(ctx, 0, &disp) == EXR_ERR_SUCCESS &&
        (dw.min.x != disp.min.x || dw.min.y != disp.min.y || dw.max.x != disp.max.x ||
         dw.max.y != disp.max.y) &&
        disp.min.x == 0 && disp.min.y == 0 && dw.min.x >= 0 && dw.min.y >= 0 &&
        dw.max.x <= disp.max.x && dw.max.y <= disp.max.y) {
        m->x0 = dw.min.x;
        m->y0 = dw.min.y;
        m->full_w = disp.max.x + 1;
        m->full_h = disp.max.y + 1;
    }
    return 0;
}

static tex_map *decode(exr_context_initializer_t *initp, const char *name, tex_map ***levels,
                       int *nlevels)
{
    exr_context_initializer_t init = *initp;
    exr_context_t ctx = NULL;
    exr_decode_pipeline_t dec;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *cl;
    exr_result_t rv;
    tex_map *m = NULL;
    int lines, order[4], nc;

    memset(&dec, 0, sizeof dec);
    init.error_handler_fn = on_exr_error;
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE | EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    init.max_image_width = TEX_MAP_MAX_SIDE;
    init.max_image_height = TEX_MAP_MAX_SIDE;
    tex_error("unknown error");

    if ((rv = exr_start_read(&ctx, name, &init))) {
        tex_error("not a valid OpenEXR stream (%s)", exr_get_default_error_message(rv));
        goto fail;
    }
    if (decode_header(ctx, &dw, &cl, &lines) < 0)
        goto fail;
    nc = order_channels(cl, order);
    if (tex_input_check_decoded(dw.max.x - dw.min.x + 1LL, dw.max.y - dw.min.y + 1LL, nc) < 0 ||
        !(m = tex_map_new(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, nc)) ||
        header_attrs(ctx, cl, order, dw, name, m) < 0)
        goto fail;
    exr_ran_short = 0;
    if (decode_chunks(ctx, &dec, dw, lines, order, m, 0) < 0)
        goto fail;
    if (levels && lines == 0 && decode_levels(ctx, &dec, dw, order, m, levels, nlevels) < 0)
        goto fail;
    exr_decoding_destroy(ctx, &dec);
    exr_finish(&ctx);
    return m;
fail:
    if (levels && *levels) {
        for (int l = 1; l < *nlevels; l++)
            tex_map_free((*levels)[l]);
        free(*levels);
        *levels = NULL;
    }
    if (ctx) {
        exr_decoding_destroy(ctx, &dec);
        exr_finish(&ctx);
    }
    tex_map_free(m);
    return NULL;
}

int tex_exr_probe(const char *path, tex_map *head)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    exr_attr_box2i_t dw, disp;
    const exr_attr_chlist_t *cl;
    int lines, order[4];
    exr_result_t rv;

    memset(head, 0, sizeof *head);
    init.error_handler_fn = on_exr_error;
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE;
    init.max_image_width = TEX_MAP_MAX_SIDE;
    init.max_image_height = TEX_MAP_MAX_SIDE;
    tex_error("unknown error");
    if ((rv = exr_start_read(&ctx, path, &init))) {
        if (ctx)
            exr_finish(&ctx);
        return tex_error("%s: not a readable OpenEXR file (%s)", path,
                         exr_get_default_error_message(rv));
    }
    if (decode_header(ctx, &dw, &cl, &lines) < 0 ||
        (rv = exr_get_display_window(ctx, 0, &disp))) {
        if (rv)
            tex_error("corrupt OpenEXR stream (%s)", exr_get_default_error_message(rv));
        exr_finish(&ctx);
        tex_error_context(path);
        return -1;
    }
    head->nc = order_channels(cl, order);
    head->w = dw.max.x - dw.min.x + 1;
    head->h = dw.max.y - dw.min.y + 1;
    head->x0 = dw.min.x;
    head->y0 = dw.min.y;
    head->full_w = disp.max.x - disp.min.x + 1;
    head->full_h = disp.max.y - disp.min.y + 1;
    exr_finish(&ctx);
    return 0;
}

/* ---- reading a band of rows at a time ---- */

struct tex_rows_reader {
    exr_context_t ctx;
    exr_decode_pipeline_t dec;
    exr_attr_box2i_t dw;
    struct rstream rs;   /* a pipe's window, when reading one */
    int file;            /* a file's descriptor, when reading one, else -1 */
    int lines, order[4], first;
    tex_map *chunk;      /* the rows of the chunk decoded last */
    int cy;              /* its first row (relative to the data window), -1: none */
};

/* A file read at any offset, its size not told to the core: a chunk past the end of a cut
 * file is read short, and says "truncated" as a pipe's does. */
static int64_t read_file(exr_const_context_t ctxt, void *ud, void *dst, uint64_t sz,
                         uint64_t off, exr_stream_error_func_ptr_t ecb)
{
    const int *fd = ud;
    uint64_t got = 0;
    (void)ctxt;
    (void)ecb;
    while (got < sz) {
        ssize_t n = pread(*fd, (char *)dst + got, sz - got, (off_t)(off + got));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        got += (uint64_t)n;
    }
    exr_ran_short |= got < sz;
    return (int64_t)got;
}

/* The tiled map on r's pipe decoded whole, from the bytes r's window holds from offset 0
 * on (the header's) and the rest of the pipe: NULL with the error set, naming name. */
static tex_map *rows_whole(tex_rows_reader *r, const char *name)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    tex_map *m;

    exr_finish(&r->ctx);
    r->ctx = NULL;
    if (r->rs.base != 0) { /* the header alone passed the window's 1 MiB */
        tex_error("%s: a tiled stream with a header over 1 MiB", name);
        return NULL;
    }
    init.user_data = &r->rs;
    init.read_fn = read_stream;
    init.size_fn = size_unknown;
    if (!(m = decode(&init, name, NULL, NULL))) {
        rstream_limit_word(&r->rs);
        tex_error_context(name);
    }
    return m;
}

tex_rows_reader *tex_rows_open(int fd, const void *prefix, size_t prefix_len, const char *path,
                               const char *name, tex_map *head, tex_map **whole)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    tex_rows_reader *r = calloc(1, sizeof *r);
    const exr_attr_chlist_t *cl;
    exr_result_t rv;

    memset(head, 0, sizeof *head);
    if (whole)
        *whole = NULL;
    if (!r) {
        tex_error("out of memory");
        return NULL;
    }
    r->cy = -1;
    r->first = 1;
    r->file = -1;
    init.error_handler_fn = on_exr_error;
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE | EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    init.max_image_width = TEX_MAP_MAX_SIDE;
    init.max_image_height = TEX_MAP_MAX_SIDE;
    if (!path) { /* a pipe: the stream's window */
        if (rstream_open(&r->rs, fd, name, prefix, prefix_len) < 0)
            goto fail;
        init.user_data = &r->rs;
        init.read_fn = read_stream;
        init.size_fn = size_unknown;
    } else if ((r->file = open(path, O_RDONLY | O_CLOEXEC)) < 0) {
        tex_error("%s: %s", name, strerror(errno));
        goto fail;
    } else {
        init.user_data = &r->file;
        init.read_fn = read_file;
        init.size_fn = size_unknown;
    }
    tex_error("unknown error");
    if ((rv = exr_start_read(&r->ctx, path ? path : name, &init))) {
        rstream_limit_word(&r->rs);
        if (!r->rs.over)
            tex_error("not a valid OpenEXR stream (%s)", exr_get_default_error_message(rv));
        tex_error_context(name);
        goto fail;
    }
    if (decode_header(r->ctx, &r->dw, &cl, &r->lines) < 0) {
        tex_error_context(name);
        goto fail;
    }
    if (r->lines <= 0 && whole && !path) {
        *whole = rows_whole(r, name);
        goto fail;
    }
    if (r->lines <= 0) {
        tex_error("%s: tiled: read whole", name);
        goto fail;
    }
    head->nc = order_channels(cl, r->order);
    head->w = r->dw.max.x - r->dw.min.x + 1;
    head->h = r->dw.max.y - r->dw.min.y + 1;
    if (tex_input_check_rows(head->w, head->h, head->nc) < 0 || /* as decode() refuses */
        (!path && tex_input_max_rows(head->w, head->h, cl->num_channels,
                                      (size_t)(r->rs.base + r->rs.len), &r->rs.max) < 0)) {
        tex_error_context(name);
        goto fail;
    }
    if (header_attrs(r->ctx, cl, r->order, r->dw, name, head) < 0)
        goto fail;
    if (!(r->chunk = tex_map_new(head->w, r->lines, head->nc)))
        goto fail;
    return r;
fail:
    free(head->history);
    head->history = NULL;
    r->rs.fd = -1; /* the caller's still */
    tex_rows_close(r);
    return NULL;
}

/* A chunk whose rows the request holds whole decodes into them where they go; one it holds
 * in part (a compressed chunk's, the band's edge) into r's chunk, kept for the next request */
int tex_rows_read(tex_rows_reader *r, int y, int n, float *rows, const char *name)
{
    const tex_map *c = r->chunk;
    size_t row = (size_t)c->w * c->nc;

    for (int k = y; k < y + n;) {
        if (r->cy < 0 || k < r->cy || k >= r->cy + r->lines) {
            exr_chunk_info_t ci;
            exr_result_t rv;
            int cy = k - k % r->lines, direct = cy == k && k + r->lines <= y + n;
            tex_map at = *c;
            if (direct)
                at.px = rows + (size_t)(k - y) * row;
            exr_ran_short = 0; /* a leader read short: the data ended before it */
            if ((rv = exr_read_scanline_chunk_info(r->ctx, 0, r->dw.min.y + cy, &ci))) {
                chunk_error(rv, "scanline", cy);
                rstream_limit_word(&r->rs);
                tex_error_context(name);
                return -1;
            }
            r->cy = -1;
            if (decode_one(r->ctx, &r->dec, &ci, r->first, r->order, &at, 0, 0) < 0) {
                if (exr_ran_short) /* at the chunk's row of the map, not of the chunk */
                    chunk_error(0, "scanline", cy);
                rstream_limit_word(&r->rs);
                tex_error_context(name);
                return -1;
            }
            r->first = 0;
            if (direct) {
                k += r->lines;
                continue;
            }
            r->cy = cy;
        }
        memcpy(rows + (size_t)(k - y) * row, tex_map_row(c, k - r->cy), row * sizeof *rows);
        k++;
    }
    return 0;
}

void tex_rows_close(tex_rows_reader *r)
{
    if (!r)
        return;
    if (r->ctx) {
        exr_decoding_destroy(r->ctx, &r->dec);
        exr_finish(&r->ctx);
    }
    tex_map_free(r->chunk);
    if (r->file >= 0)
        close(r->file);
    if (r->rs.buf && r->rs.fd > 0) /* a pipe other than standard input */
        close(r->rs.fd);
    free(r->rs.buf);
    free(r);
}
