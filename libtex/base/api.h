/* api.h - what libtex exports: the declarations of its installed headers
 *
 * libtex is compiled with hidden visibility (-fvisibility=hidden), so libtex.so exports
 * a function or a variable only where an installed header declares it between
 * TEX_API_BEGIN and TEX_API_END (which also give C++ its extern "C"):
 *
 *   #include "../base/api.h"
 *   TEX_API_BEGIN
 *   tex_map *tex_map_new(int w, int h, int nc);
 *   TEX_API_END
 *
 * The headers that stay inside libtex (render/scene.h, lang/expr.h, base/simd.h ...) use
 * neither: what they declare is libtex's own, shared between its files and hidden from
 * programs.  tests/house/install.sh checks that libtex.so exports exactly what the installed
 * headers declare.
 */
#ifndef TEX_API_H
#define TEX_API_H

#if defined(__GNUC__) || defined(__clang__)
#define TEX_API_PUSH_ _Pragma("GCC visibility push(default)")
#define TEX_API_POP_ _Pragma("GCC visibility pop")
#else
#define TEX_API_PUSH_
#define TEX_API_POP_
#endif

#ifdef __cplusplus
#define TEX_API_BEGIN TEX_API_PUSH_ extern "C" {
#define TEX_API_END } TEX_API_POP_
#else
#define TEX_API_BEGIN TEX_API_PUSH_
#define TEX_API_END TEX_API_POP_
#endif

#endif
