/* cli.h - the tools' shared command-line front end
 *
 * The one part of libtex that prints and exits: it stands for the tool's main.
 * A tool includes this header and finds here
 *   options.h   its options parsed from parameter rows (the common ones by a mask,
 *               its own rows), the operands counted, --help and --version;
 *   message.h   errors "t_noise: error: ..." on stderr, exit 2 for usage errors and
 *               1 for runtime ones, warnings, the progress bar;
 *   maps.h      its maps read and written (-o, standard output, the history), whole
 *               or a band of rows at a time;
 *   lockstep.h  per-pixel work over several maps read a band at a time, in step;
 *   generate.h  the whole main of a generator tool.
 *
 *   static struct opts { int json; } o;
 *   static const struct tex_param rows[] = {TEX_FLAG(struct opts, json, 0, "..."), {0}};
 *   static const struct tex_tool tool = {"t_info", "[MAP]", "statistics of a map",
 *                                        0, rows, 0, 1};
 *   struct tex_common c;
 *   int i = tex_cli_parse(&tool, argc, argv, &c, &o);   // argv[i..] are the operands
 *   tex_map *m = tex_cli_read(i < argc ? argv[i] : "-");
 *   ...
 *   tex_cli_write(m, &c);
 */
#ifndef TEX_CLI_H
#define TEX_CLI_H

#include <stdint.h>

#include "../base/map.h"
#include "../base/param.h"
#include "../prim/prim.h"
#include "generate.h"
#include "lockstep.h"
#include "maps.h"
#include "message.h"
#include "options.h"

#endif
