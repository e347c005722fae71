/* limit.h - the one limit on what a reader takes in
 *
 *   size_t max;
 *   if (tex_input_max(&max) < 0) return -1;            // $TEXTURA_MAX_INPUT, or 2 GiB
 *   if (tex_input_check_decoded(w, h, nc) < 0)  // before allocating a map read
 *       return NULL;
 *
 * Every reader of a map, a points file or an image inside a scene or script
 * stops at max bytes actually read, so /dev/zero, a FIFO and a file that
 * grows are all bounded, and refuses a map whose declared size, as float
 * samples (w x h x channels x 4 bytes), is larger: a compressed file (an
 * 875 KB PNG of 30000 x 30000 zeros) is refused before it is decompressed.
 * The limit is $TEXTURA_MAX_INPUT, in bytes with an optional suffix K, M or
 * G (powers of 1024), 1K at least; unset or empty, 2 GiB (textura(5)).
 *
 * A read of a map in bands of rows (io/stream.h's rows reader) holds a band,
 * not the map: with the variable unset, its header is read under the 2 GiB
 * limit and its rows under the size the header declares (tex_input_max_rows),
 * so a streaming pipeline of 65536 x 65536 maps needs no setting; with the
 * variable set, the limit is the variable's, as for any read.
 */
#ifndef TEX_LIMIT_H
#define TEX_LIMIT_H

#include <stddef.h>

#include "../base/api.h"

TEX_API_BEGIN

#define TEX_INPUT_MAX_DEFAULT ((size_t)2 << 30)

/* The limit into *max: 0, or -1 with a usage error naming the variable when it is not
 * a size. */
int tex_input_max(size_t *max);

/* 0 when a w x h x nc map of float fits the limit, else -1 with an error giving the
 * declared size and the limit (the caller adds the input's name). */
int tex_input_check_decoded(long long w, long long h, long long nc);

/* The same for a map read in bands of rows: the variable's limit when it is set, else
 * none (the map is never held). */
int tex_input_check_rows(long long w, long long h, long long nc);
/* The limit on the bytes of a w x h x nc map's stream read in bands, head bytes of it read
 * already (its header): the variable's when it is set, else a bound on what a valid stream
 * of that map holds; -1 as tex_input_max. */
int tex_input_max_rows(long long w, long long h, long long nc, size_t head, size_t *max);

TEX_API_END

#endif
