/* generate.h - the whole main of a generator tool
 *
 * A tool t_NAME that samples one primitive is its descriptor and one call:
 *
 *   int main(int argc, char **argv) { return tex_generate_main(&tex_prim_circle, argc, argv); }
 *
 * The options are the primitive's rows and the common ones (-o and the output's,
 * -s, -S, --window; --tile and --ids/--palette where the primitive has them).  Where
 * the output is a scanline EXR and the sampler does not need the whole grid, the map
 * is sampled and written a band of rows at a time: the same pixels, in bounded memory.
 */
#ifndef TEX_CLI_GENERATE_H
#define TEX_CLI_GENERATE_H

#include "../base/api.h"
#include "../base/param.h"
#include "../prim/prim.h"

TEX_API_BEGIN

/* The whole main of a generator tool t_NAME: parse, sample, write. */
int tex_generate_main(const struct tex_primitive *p, int argc, char **argv);
/* The same for a tool named name whose options are more than the
 * primitive's: rows over opts, a struct that begins with the primitive's
 * parameter struct (p->params_size bytes, the defaults copied in before
 * parsing); operands: the usage text of its one operand ("" for none). */
int tex_generate_main_rows(const struct tex_primitive *p, const char *name,
                           const char *operands, const struct tex_param *rows, void *opts,
                           int argc, char **argv);

TEX_API_END
#endif
