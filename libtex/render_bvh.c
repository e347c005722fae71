/* render_bvh.c - bounding-volume hierarchy over the top-level objects
 *
 * Bounded objects go into a binary tree split at the median of the
 * longest axis of their centres; unbounded ones (planes, CSG trees built
 * on them) are tested one by one.  Traversal visits the nearer child
 * first and shrinks tmax as hits are found.
 */
#include <stdlib.h>

#include "error.h"
#include "render.h"

struct node {
    struct tex_bounds b;
    int left, right; /* children, or -1 */
    int first, count; /* leaves: objects[first..first+count) */
};

struct tex_bvh {
    struct node *nodes;
    int nnodes;
    const struct tex_object **obs; /* bounded, in tree order */
    const struct tex_object **unb; /* unbounded */
    int nunb;
};

static struct tex_bounds merge(struct tex_bounds a, struct tex_bounds b)
{
    struct tex_bounds r = {tex_v3_make(fmin(a.lo.x, b.lo.x), fmin(a.lo.y, b.lo.y),
                                       fmin(a.lo.z, b.lo.z)),
                           tex_v3_make(fmax(a.hi.x, b.hi.x), fmax(a.hi.y, b.hi.y),
                                       fmax(a.hi.z, b.hi.z))};
    return r;
}

static double centre(const struct tex_object *o, int axis)
{
    return tex_v3_get(o->wb.lo, axis) + tex_v3_get(o->wb.hi, axis);
}

static int build(struct tex_bvh *t, int first, int count)
{
    int id = t->nnodes++;
    struct node *n = &t->nodes[id];
    n->b = t->obs[first]->wb;
    for (int i = 1; i < count; i++)
        n->b = merge(n->b, t->obs[first + i]->wb);
    n->left = n->right = -1;
    n->first = first;
    n->count = count;
    if (count <= 2)
        return id;
    tex_v3 ext = tex_v3_sub(n->b.hi, n->b.lo);
    int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    /* insertion sort by centre: stable and deterministic, fine for thousands */
    for (int i = first + 1; i < first + count; i++) {
        const struct tex_object *o = t->obs[i];
        int j = i - 1;
        while (j >= first && centre(t->obs[j], axis) > centre(o, axis)) {
            t->obs[j + 1] = t->obs[j];
            j--;
        }
        t->obs[j + 1] = o;
    }
    int half = count / 2;
    int l = build(t, first, half);
    int r = build(t, first + half, count - half);
    t->nodes[id].left = l;
    t->nodes[id].right = r;
    t->nodes[id].count = 0;
    return id;
}

struct tex_bvh *tex_bvh_build(struct tex_object **obs, int n)
{
    struct tex_bvh *t = calloc(1, sizeof *t);
    if (!t)
        return NULL;
    t->obs = malloc((n ? n : 1) * sizeof *t->obs);
    t->unb = malloc((n ? n : 1) * sizeof *t->unb);
    t->nodes = malloc((2 * n + 1) * sizeof *t->nodes);
    if (!t->obs || !t->unb || !t->nodes) {
        tex_bvh_free(t);
        tex_error("out of memory building the BVH");
        return NULL;
    }
    int nb = 0;
    for (int i = 0; i < n; i++) {
        if (tex_object_bounds(obs[i]))
            t->obs[nb++] = obs[i];
        else
            t->unb[t->nunb++] = obs[i];
    }
    if (nb)
        build(t, 0, nb);
    return t;
}

void tex_bvh_free(struct tex_bvh *b)
{
    if (!b)
        return;
    free(b->nodes);
    free(b->obs);
    free(b->unb);
    free(b);
}

/* Slab test against [tmin, tmax]; the entry distance in *t0. */
static inline double mind(double a, double b)
{
    return a < b ? a : b;
}
static inline double maxd(double a, double b)
{
    return a > b ? a : b;
}

/* Slab test against [tmin, tmax]; the entry distance in *t0.  Plain compares,
 * not fmin/fmax, which are library calls at -O2 (NaN rules). */
static inline int hit_box(const struct tex_bounds *b, tex_v3 o, tex_v3 inv, double tmin,
                          double tmax, double *t0)
{
    double a = (b->lo.x - o.x) * inv.x, c = (b->hi.x - o.x) * inv.x;
    double lo = maxd(tmin, mind(a, c)), hi = mind(tmax, maxd(a, c));
    a = (b->lo.y - o.y) * inv.y, c = (b->hi.y - o.y) * inv.y;
    lo = maxd(lo, mind(a, c)), hi = mind(hi, maxd(a, c));
    a = (b->lo.z - o.z) * inv.z, c = (b->hi.z - o.z) * inv.z;
    lo = maxd(lo, mind(a, c)), hi = mind(hi, maxd(a, c));
    *t0 = lo;
    return lo <= hi;
}

/* The first boundary of ob beyond tmin and before *tmax. */
static int first_hit(const struct tex_object *ob, tex_v3 o, tex_v3 d, double tmin, double *tmax,
                     struct tex_hit *hit)
{
    struct tex_spans s;
    tex_object_spans(ob, o, d, &s);
    for (int i = 0; i < s.n; i++) {
        const struct tex_hit *h = s.in[i].t > tmin ? &s.in[i] : s.out[i].t > tmin ? &s.out[i] : NULL;
        if (!h)
            continue;
        if (h->t < *tmax && h->leaf) {
            *hit = *h;
            *tmax = h->t;
            return 1;
        }
        return 0;
    }
    return 0;
}

int tex_bvh_trace(const struct tex_bvh *t, tex_v3 o, tex_v3 d, double tmin, double tmax,
                  struct tex_hit *hit)
{
    return tex_bvh_trace_any(t, o, d, tmin, tmax, 0, hit);
}

int tex_bvh_trace_any(const struct tex_bvh *t, tex_v3 o, tex_v3 d, double tmin, double tmax,
                      int any, struct tex_hit *hit)
{
    int found = 0;
    for (int i = 0; i < t->nunb; i++) {
        found |= first_hit(t->unb[i], o, d, tmin, &tmax, hit);
        if (found && any)
            return 1;
    }
    if (!t->nnodes)
        return found;
    /* IEEE division gives +-inf for zero components, which the slab test handles
     * except for 0 * inf; nudge zeros instead. */
    tex_v3 inv = tex_v3_make(1 / (d.x != 0 ? d.x : 1e-300), 1 / (d.y != 0 ? d.y : 1e-300),
                             1 / (d.z != 0 ? d.z : 1e-300));
    int stack[128], sp = 0;
    double t0;
    if (!hit_box(&t->nodes[0].b, o, inv, tmin, tmax, &t0))
        return found;
    stack[sp++] = 0;
    while (sp) {
        const struct node *n = &t->nodes[stack[--sp]];
        if (!hit_box(&n->b, o, inv, tmin, tmax, &t0))
            continue;
        if (n->count) {
            for (int i = 0; i < n->count; i++)
                found |= first_hit(t->obs[n->first + i], o, d, tmin, &tmax, hit);
            if (found && any)
                return 1;
            continue;
        }
        double tl, tr;
        int hl = hit_box(&t->nodes[n->left].b, o, inv, tmin, tmax, &tl);
        int hr = hit_box(&t->nodes[n->right].b, o, inv, tmin, tmax, &tr);
        if (hl && hr && sp < 126) {
            /* push the farther first so the nearer is visited first */
            stack[sp++] = tl <= tr ? n->right : n->left;
            stack[sp++] = tl <= tr ? n->left : n->right;
        } else if (hl && sp < 127) {
            stack[sp++] = n->left;
        } else if (hr && sp < 127) {
            stack[sp++] = n->right;
        }
    }
    return found;
}

int tex_scene_trace(const struct tex_scene *s, tex_v3 o, tex_v3 d, double tmin, double tmax,
                    struct tex_hit *hit)
{
    return tex_bvh_trace(s->bvh, o, d, tmin, tmax, hit);
}
