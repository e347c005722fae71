/* terminal.h - a map drawn in a terminal: sixel or the kitty graphics protocol
 *
 * For looking at a map from the shell without opening a viewer (t_info
 * --preview).  The map is drawn at its own size, one terminal pixel per
 * texel, so the caller shrinks it first (t_info takes box means as rows pass).
 * Values are taken as display values, as the other formats store them:
 * clamped to [0, 1], no transfer function; a grey map is grey, a 2-channel
 * map red and green, an alpha channel composes over black.
 *
 *   sixel  DEC's sixel graphics (xterm -ti vt340, mlterm, foot, WezTerm,
 *          Contour, mintty...): at most 256 registers chosen for the map by
 *          median cut, Floyd-Steinberg error diffusion between them (so a
 *          smooth ramp stays smooth and a white marble white), rows of six
 *          pixels, runs compressed (DEC's "!" repeat).
 *   kitty  the kitty terminal's graphics protocol (kitty, WezTerm,
 *          Konsole, Ghostty): 24-bit RGB, base64 in chunks of 4096.
 *
 *   if (tex_terminal_write(stdout, thumb, TEX_TERMINAL_SIXEL) < 0) ...
 *
 * tex_terminal_guess() picks the protocol from the environment: kitty where
 * KITTY_WINDOW_ID is set or TERM names kitty or ghostty, sixel otherwise.
 */
#ifndef TEX_TERMINAL_H
#define TEX_TERMINAL_H

#include <stdio.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

enum tex_terminal_proto { TEX_TERMINAL_SIXEL, TEX_TERMINAL_KITTY };

enum tex_terminal_proto tex_terminal_guess(void);
/* Draw m (1..4 channels) at the cursor; -1 with tex_error() on a write error. */
int tex_terminal_write(FILE *fp, const tex_map *m, enum tex_terminal_proto proto);

TEX_API_END
#endif
