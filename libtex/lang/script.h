/* script.h - the pattern composition language (thesis 5.2.4.2)
 *
 * A script builds one texture map: a tessellation of cells (rectangles,
 * bricks, hexagons or triangles), each showing a named image, where images
 * come from files, standard input or primitives and are combined by
 * transforms (expand, rotate, scale, shift, clipping, filter with every
 * t_filter operation, tile, warp) and operators (over, under, and, or,
 * xor, +, -, *, min, max).  The thesis's Portuguese keywords (celula,
 * retangular) and its operators written as functions (+_up(P1,P2),
 * AND(P1,P2), Rotate(alpha,P)) are read too.  man 5 t_compose is the
 * reference; the thesis's example, in English:
 *
 *   tessellation test2;
 *   size 400 by 400;
 *   tessellation rectangular;
 *   cell 200 by 200;
 *   images
 *     image1 = "leo.exr" 200 by 200;
 *     image4; image5; image6;
 *   end images;
 *   image4 = expand image1 to 300 by 300 background 0,0;
 *   image5 = rotate image4 by 20 around 150, 150;
 *   image6 = clipping image5 from 50,50 to 250,250;
 *   built with
 *     (1,1) image4; (2,1) image5; (1,2) image6; (2,2) image1;
 *   end tessellation;
 *
 * Definitions are declarative: each name is defined once, in any order,
 * and evaluated when first needed; a definition that needs itself is an
 * error.  Errors name the script, line and column:
 * "pattern.tc:7:14: undefined image 'imag1'".
 *
 *   struct tex_script_opts o = TEX_SCRIPT_DEFAULTS;
 *   tex_map *m = tex_script_run(text, len, "pattern.tc", &o);
 *
 * Limits keep hostile scripts cheap: every image is at most max_pixels
 * pixels, and files (and standard input) are read only if allowed.
 */
#ifndef TEX_SCRIPT_H
#define TEX_SCRIPT_H

#include <stddef.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

struct tex_script_opts {
    long long max_pixels; /* largest image, in pixels */
    int allow_files;      /* 0: quoted file names are an error */
    int allow_stdin;      /* 0: "-" is an error (e.g. the script came from stdin) */
    int max_blur;         /* largest blur radius (sigma), pixels */
};
#define TEX_SCRIPT_DEFAULTS {64LL << 20, 1, 1, 256}

/* Run a script; NULL with tex_errmsg() ("name:line:col: ...") on failure.
 * Script mistakes are usage errors, unreadable files runtime errors. */
tex_map *tex_script_run(const char *text, size_t len, const char *name,
                        const struct tex_script_opts *o);

TEX_API_END
#endif
