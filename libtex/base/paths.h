/* paths.h - where an installed Textura finds its parts, found at run time
 *
 *   char p[PATH_MAX];
 *   snprintf(p, sizeof p, "%s/textura/textura-png.so", tex_install_dir(TEX_DIR_LIB));
 *   snprintf(p, sizeof p, "%s/patterns/materials.txt", tex_install_dir(TEX_DIR_DATA));
 *
 * The prefix is taken from the object that holds libtex, once: libtex.so's
 * own folder is LIBDIR, a program's folder (libtex.a linked in) is
 * PREFIX/bin.  The layout under the prefix is the build's (LIBDIR and
 * DATADIR relative to PREFIX), so a tree built for one prefix and installed
 * with `make install PREFIX=/x`, or staged with DESTDIR and moved, finds
 * its bridges and data files at /x; so does a build tree (build/bin,
 * build/lib, build/share).  When the object lies outside such a layout, or
 * the folder found does not exist, the build-time folder is used.
 */
#ifndef TEX_PATHS_H
#define TEX_PATHS_H

#include "api.h"

TEX_API_BEGIN

enum tex_dir {
    TEX_DIR_LIB, /* LIBDIR: the bridges are in its textura/ folder */
    TEX_DIR_DATA /* DATADIR: palettes/, patterns/ (materials.txt) */
};

/* The folder, without a trailing '/'; never NULL. */
const char *tex_install_dir(enum tex_dir d);

TEX_API_END
#endif
