/* matdb.h - the materials database ("banco de materiais", Ferreira 1991, section 5)
 *
 * Optical constants per wavelength, read from a text file (format in
 * textura-materials(5); the shipped one is patterns/materials.txt):
 *
 *   material gold conductor
 *   source Johnson & Christy, Phys. Rev. B 6, 4370 (1972)
 *   nk 495.9 1.04 1.833          # wavelength (nm), n, k
 *   ...
 *   end
 *   material bk7 dielectric
 *   sellmeier 1.03961212 0.231792344 1.01046945 0.00600069867 0.0200179144 103.560653
 *   end
 *
 * A dielectric gives its index as `ior N`, `cauchy A B [C]`
 * (n = A + B/l^2 + C/l^4, l in micrometres), `sellmeier B1 B2 B3 C1 C2 C3`
 * (n^2 = 1 + sum Bi l^2/(l^2 - Ci), l in micrometres, Ci in um^2) or `nk`
 * rows; a conductor needs `nk` rows.  Every material is stored as two curves
 * n(l), k(l) at 1 nm over 380-780 nm (spectrum.h), so the renderer samples
 * them into its bands with tex_bands_sample().
 *
 *   struct tex_matdb db;
 *   if (tex_matdb_read(&db, "patterns/materials.txt") < 0) die(tex_errmsg());
 *   const struct tex_matdb_entry *m = tex_matdb_find(&db, "gold");  // NULL + error
 *   tex_matdb_free(&db);
 *
 * Errors carry "file:line: " and are usage errors (exit 2): unknown keyword,
 * unsorted or negative wavelengths, k < 0, n <= 0, a Sellmeier or Cauchy
 * formula giving n <= 0 in 380-780 nm, a material without data, a duplicate
 * name, a missing `end`.  tex_matdb_find() of an unknown name is a usage
 * error listing the known names.
 */
#ifndef TEX_MATDB_H
#define TEX_MATDB_H

#include "../base/api.h"
#include "spectrum.h"

TEX_API_BEGIN

#define TEX_MATDB_NAME 32

enum tex_matdb_kind { TEX_DIELECTRIC, TEX_CONDUCTOR };

struct tex_matdb_entry {
    char name[TEX_MATDB_NAME];
    enum tex_matdb_kind kind;
    tex_curve n, k;
    char *source; /* citation, may be NULL */
};

struct tex_matdb {
    int count;
    struct tex_matdb_entry *m;
};

int tex_matdb_read(struct tex_matdb *db, const char *path);
/* Parse from memory; `name` is used in messages. */
int tex_matdb_parse(struct tex_matdb *db, const char *text, const char *name);
const struct tex_matdb_entry *tex_matdb_find(const struct tex_matdb *db, const char *name);
void tex_matdb_free(struct tex_matdb *db);

TEX_API_END
#endif
