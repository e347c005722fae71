/* render_bvh.c - bounding-volume hierarchy over the top-level objects
 *
 * Bounded objects go into a binary tree built with the surface-area
 * heuristic over their centres (sorted per axis, ties broken by index, so
 * the tree is deterministic); leaves hold up to LEAF_MAX objects.  Unbounded
 * ones (planes, CSG trees built on them) are tested one by one, first, so
 * their hits shrink the search before the tree is entered.
 *
 * Each object gets a fast path chosen at build time: a sphere placed by a
 * similarity (translate, rotate, uniform scale) is intersected in world
 * space, a plane through its object-space y row alone; other leaves pay for
 * the transform once a ray meets their box, CSG trees for their interval
 * lists.  Traversal is ordered (nearer child first), skips nodes entered
 * beyond the closest hit, and a shadow query (any = 1) stops at the first
 * hit; it goes four children a node (struct quad: the binary tree with every
 * other level folded in), whose boxes one ray tests in vector lanes; a packet's eye rays walk
 * it together (tex_scene_trace_packet), a node's boxes against every ray still in it.
 * tex_scene_transmit visits every object along a shadow ray once, in any order: the light
 * passing is the product of Kt over the surfaces crossed.  A ray leaving an object from a hull leaf (struct tex_object)
 * does not test it (it cannot meet it again), and eye rays that a view of
 * the tree's box shows beside it (tex_scene_view) test the unbounded objects
 * alone; beside it, they skip the bounded objects whose boxes the view shows
 * them beside (tex_view_objects: a packet's rays at once).
 *
 * A CSG block of many operands is a tree too: the parser joins them as a balanced tree
 * (tex_csg_balanced), and once their world boxes are known they are joined again by
 * median splits along the longest axis (tex_csg_spatial), so that a union of many
 * disjoint objects culls whole halves by their boxes, as the scene's BVH does.
 */
#define _GNU_SOURCE /* qsort_r */
#include <stdlib.h>

#include "base/error.h"
#include "render/scene.h"
#include "render/x86/bvh_x86.h"

#define LEAF_MAX 8

/* Relative costs for the surface-area heuristic: one node visit tests two
 * boxes; a world-space sphere or plane test is cheaper than a box test. */
#define COST_NODE 2.0

enum pkind { PK_SPHERE, PK_PLANE, PK_LEAF, PK_CSG };

/* One top-level object and its fast path. */
struct prim {
    tex_v3 a;  /* sphere: world centre; plane: the y row of to_obj */
    double b;  /* sphere: radius squared; plane: the row's offset */
    int kind;
    struct tex_bounds box; /* a bounded leaf's world box, a little widened */
    const struct tex_object *ob;
};

struct node {
    struct tex_bounds b;
    int first; /* inner: the right child (the left is the next node); leaf: first prim */
    int count; /* leaf: number of prims; 0 for inner nodes */
};

/* A node of the four-wide tree the closest-hit walk takes: the binary tree with every other
 * level folded in (an inner node's grandchildren, where its children are inner), its children's
 * boxes lane by lane for one test of all.  Child c: a leaf's prims first[c].. (count[c] > 0)
 * or the quad first[c]; mask: its children's lanes (2 to 4). */
struct quad {
    struct tex_box4 b;
    int first[4], count[4];
    int mask;
} __attribute__((aligned(64)));

struct tex_bvh {
    struct node *nodes;
    struct quad *quads; /* quads[0]: the root's, where it is inner */
    int nnodes, nquads;
    struct prim *prims; /* bounded, in tree order */
    int nprims;
    struct prim *unb;   /* unbounded */
    int nunb;
};

/* r's inv and dd from its d: what a shadow ray's walk reads (no idd: its division is the
 * closest hit's alone) */
static inline void ray_slabs(struct tex_bvh_ray *r)
{
    r->inv = tex_v3_slab_inv(r->d);
    r->dd = tex_v3_dot(r->d, r->d);
}

static inline void ray_setup(struct tex_bvh_ray *r, const tex_v3 *o, const tex_v3 *d)
{
    r->o = *o;
    r->d = *d;
    ray_slabs(r);
    r->idd = 1 / r->dd;
}

static double area(struct tex_bounds b)
{
    tex_v3 e = tex_v3_sub(b.hi, b.lo);
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

/* The fast path of a top-level object. */
static void classify(struct prim *p, const struct tex_object *ob)
{
    p->ob = ob;
    p->kind = ob->op == TEX_CSG_LEAF ? PK_LEAF : PK_CSG;
    if (p->kind != PK_LEAF)
        return;
    const double(*m)[4] = ob->to_world.m;
    if (ob->kind == TEX_SHAPE_SPHERE) {
        /* a similarity keeps the sphere round: orthogonal columns of equal length */
        tex_v3 c0 = tex_v3_make(m[0][0], m[1][0], m[2][0]);
        tex_v3 c1 = tex_v3_make(m[0][1], m[1][1], m[2][1]);
        tex_v3 c2 = tex_v3_make(m[0][2], m[1][2], m[2][2]);
        double s2 = tex_v3_dot(c0, c0), tol = 1e-12 * s2;
        if (fabs(tex_v3_dot(c1, c1) - s2) <= tol && fabs(tex_v3_dot(c2, c2) - s2) <= tol &&
            fabs(tex_v3_dot(c0, c1)) <= tol && fabs(tex_v3_dot(c1, c2)) <= tol &&
            fabs(tex_v3_dot(c0, c2)) <= tol && s2 > 0) {
            p->kind = PK_SPHERE;
            p->a = tex_v3_make(m[0][3], m[1][3], m[2][3]);
            p->b = s2;
        }
    } else if (ob->kind == TEX_SHAPE_PLANE) {
        const double(*q)[4] = ob->to_obj.m;
        p->kind = PK_PLANE;
        p->a = tex_v3_make(q[1][0], q[1][1], q[1][2]);
        p->b = q[1][3];
    }
}

static double cost(const struct prim *p)
{
    /* a CSG tree starts with its own box test, which rejects most rays */
    return p->kind == PK_SPHERE || p->kind == PK_PLANE ? 0.8 : p->kind == PK_LEAF ? 2 : 1.5;
}

static double centre(const struct prim *p, int axis)
{
    return tex_v3_get(p->ob->wb.lo, axis) + tex_v3_get(p->ob->wb.hi, axis);
}

struct sortkey {
    const struct prim *base;
    int axis;
};

/* Sort items (indices into the prims) by centre, then by index: deterministic. */
static int cmp_centre(const void *x, const void *y, void *arg)
{
    const struct sortkey *k = arg;
    int i = *(const int *)x, j = *(const int *)y;
    double a = centre(&k->base[i], k->axis), b = centre(&k->base[j], k->axis);
    return a < b ? -1 : a > b ? 1 : (i > j) - (i < j);
}

struct builder {
    struct tex_bvh *t;
    const struct prim *src; /* the bounded prims in input order */
    int *idx;               /* [first, first + count): the items of the node being built */
    int *tmp;
    double *rarea;          /* right-hand area times cost of a sweep */
    int nprims;
};

/* Deeper than this, split at the median: the traversal stack stays bounded. */
#define SAH_DEPTH 48

static void build(struct builder *bd, int first, int count, int depth)
{
    struct tex_bvh *t = bd->t;
    int id = t->nnodes++;
    struct node *n = &t->nodes[id];
    n->b = bd->src[bd->idx[first]].ob->wb;
    for (int i = 1; i < count; i++)
        n->b = tex_bounds_union(n->b, bd->src[bd->idx[first + i]].ob->wb);
    /* surface-area heuristic */
    double best = 0, parea = area(n->b);
    for (int i = 0; i < count; i++)
        best += cost(&bd->src[bd->idx[first + i]]);
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3 && count > 1 && parea > 0 && depth < SAH_DEPTH; axis++) {
        int *it = bd->tmp;
        struct sortkey k = {bd->src, axis};
        for (int i = 0; i < count; i++)
            it[i] = bd->idx[first + i];
        qsort_r(it, count, sizeof *it, cmp_centre, &k);
        struct tex_bounds b = bd->src[it[count - 1]].ob->wb;
        double sum = 0;
        for (int i = count - 1; i > 0; i--) {
            b = tex_bounds_union(b, bd->src[it[i]].ob->wb);
            sum += cost(&bd->src[it[i]]);
            bd->rarea[i] = area(b) * sum;
        }
        b = bd->src[it[0]].ob->wb;
        sum = 0;
        for (int i = 1; i < count; i++) {
            sum += cost(&bd->src[it[i - 1]]);
            double c = COST_NODE + (area(b) * sum + bd->rarea[i]) / parea;
            if (c < best) {
                best = c;
                best_axis = axis;
                best_split = i;
            }
            b = tex_bounds_union(b, bd->src[it[i]].ob->wb);
        }
    }
    if (best_axis < 0 && count > LEAF_MAX) { /* no better split: halve along the longest axis */
        tex_v3 e = tex_v3_sub(n->b.hi, n->b.lo);
        best_axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
        best_split = count / 2;
    }
    if (best_axis < 0) {
        n->count = count;
        n->first = bd->nprims;
        for (int i = 0; i < count; i++)
            t->prims[bd->nprims++] = bd->src[bd->idx[first + i]];
        return;
    }
    struct sortkey k = {bd->src, best_axis};
    qsort_r(bd->idx + first, count, sizeof *bd->idx, cmp_centre, &k);
    n->count = 0;
    build(bd, first, best_split, depth + 1);
    int right = t->nnodes;
    build(bd, first + best_split, count - best_split, depth + 1);
    t->nodes[id].first = right;
}

/* The quad of inner node ni and those under it: its children, each inner one's two in its
 * place, in the binary tree's order (a tie of entry distances walks them as it did) */
static int quad_of(struct tex_bvh *t, int ni)
{
    int id = t->nquads++, kid[4], n = 0;
    int two[2] = {ni + 1, t->nodes[ni].first};
    for (int i = 0; i < 2; i++) {
        const struct node *k = &t->nodes[two[i]];
        if (k->count) {
            kid[n++] = two[i];
        } else {
            kid[n++] = two[i] + 1;
            kid[n++] = k->first;
        }
    }
    struct quad *q = &t->quads[id];
    q->mask = (1 << n) - 1;
    for (int c = 0; c < 4; c++) { /* lanes past n repeat the first box, masked off */
        const struct node *k = &t->nodes[kid[c < n ? c : 0]];
        const double lo[3] = {k->b.lo.x, k->b.lo.y, k->b.lo.z};
        const double hi[3] = {k->b.hi.x, k->b.hi.y, k->b.hi.z};
        for (int a = 0; a < 3; a++)
            q->b.lo[a][c] = lo[a], q->b.hi[a][c] = hi[a];
        q->first[c] = k->first, q->count[c] = k->count;
    }
    for (int c = 0; c < n; c++)
        if (!q->count[c])
            q->first[c] = quad_of(t, kid[c]);
    return id;
}

struct tex_bvh *tex_bvh_build(struct tex_object **obs, int n)
{
    struct tex_bvh *t = calloc(1, sizeof *t);
    struct builder bd = {t, NULL, NULL, NULL, NULL, 0};
    struct prim *src = NULL;
    int m = n ? n : 1;
    if (!t)
        goto oom;
    t->prims = malloc(m * sizeof *t->prims);
    t->unb = malloc(m * sizeof *t->unb);
    t->nodes = malloc((2 * m + 1) * sizeof *t->nodes);
    src = malloc(m * sizeof *src);
    bd.idx = malloc(m * sizeof *bd.idx);
    bd.tmp = malloc(m * sizeof *bd.tmp);
    bd.rarea = malloc(m * sizeof *bd.rarea);
    if (!t->prims || !t->unb || !t->nodes || !src || !bd.idx || !bd.tmp || !bd.rarea)
        goto oom;
    int nb = 0;
    for (int i = 0; i < n; i++) {
        tex_object_hulls(obs[i]);
        if (tex_object_bounds(obs[i])) {
            bd.idx[nb] = nb;
            classify(&src[nb++], obs[i]);
        } else {
            classify(&t->unb[t->nunb++], obs[i]);
        }
    }
    /* a transformed leaf's spans cost several box tests: rays that miss its world box skip
     * them.  Widened by 1e-9 of its size: a ray that grazes the shape is not lost to
     * rounding. */
    for (int i = 0; i < nb; i++) {
        struct prim *p = &src[i];
        tex_v3 e = tex_v3_sub(p->ob->wb.hi, p->ob->wb.lo);
        double pad = 1e-9 * (e.x + e.y + e.z) + 1e-300;
        p->box.lo = tex_v3_sub(p->ob->wb.lo, tex_v3_make(pad, pad, pad));
        p->box.hi = tex_v3_add(p->ob->wb.hi, tex_v3_make(pad, pad, pad));
    }
    bd.src = src;
    if (nb)
        build(&bd, 0, nb, 0);
    t->nprims = nb;
    if (!(t->quads = aligned_alloc(64, (t->nnodes ? t->nnodes : 1) * sizeof *t->quads)))
        goto oom;
    if (t->nnodes && !t->nodes[0].count)
        quad_of(t, 0);
    free(src);
    free(bd.idx);
    free(bd.tmp);
    free(bd.rarea);
    return t;
oom:
    free(src);
    free(bd.idx);
    free(bd.tmp);
    free(bd.rarea);
    tex_bvh_free(t);
    tex_error("out of memory building the BVH");
    return NULL;
}

void tex_bvh_free(struct tex_bvh *b)
{
    if (!b)
        return;
    free(b->nodes);
    free(b->quads);
    free(b->prims);
    free(b->unb);
    free(b);
}


/* Slab test against [tmin, tmax]; the entry distance in *t0. */
static inline int hit_box(const struct tex_bounds *b, const struct tex_bvh_ray *r, double tmin,
                          double tmax, double *t0)
{
    double a = (b->lo.x - r->o.x) * r->inv.x, c = (b->hi.x - r->o.x) * r->inv.x;
    double lo = tex_maxd(tmin, tex_mind(a, c)), hi = tex_mind(tmax, tex_maxd(a, c));
    a = (b->lo.y - r->o.y) * r->inv.y, c = (b->hi.y - r->o.y) * r->inv.y;
    lo = tex_maxd(lo, tex_mind(a, c)), hi = tex_mind(hi, tex_maxd(a, c));
    a = (b->lo.z - r->o.z) * r->inv.z, c = (b->hi.z - r->o.z) * r->inv.z;
    lo = tex_maxd(lo, tex_mind(a, c)), hi = tex_mind(hi, tex_maxd(a, c));
    *t0 = lo;
    return lo <= hi;
}

/* Does r cross the surface of transformed leaf p between tmin and tmax?  -1 where it misses
 * p's box there or surely does not, 1 where it surely does, 0 where only its spans tell
 * (tex_leaf_segment: a torus's quartic only where cheap tests cannot decide) */
static inline int leaf_segment(const struct prim *p, const struct tex_bvh_ray *r, double tmin,
                               double tmax)
{
    double t0;
    if (p->ob->bounded && !hit_box(&p->box, r, tmin, tmax, &t0))
        return -1;
    return tex_leaf_segment(p->ob, &r->o, &r->d, tmin, tmax);
}

/* The spans of a transformed leaf or a CSG tree p along r into *s; 0 (none made) where r
 * has no boundary of it between tmin and tmax (the closest hit so far, or the light) that
 * cheap tests can rule out: its box, or leaf_segment. */
static inline int prim_spans(const struct prim *p, const struct tex_bvh_ray *r, double tmin,
                             double tmax, struct tex_spans *s)
{
    const struct tex_object *ob = p->ob;
    double t0;
    if (p->kind == PK_LEAF) {
        if (leaf_segment(p, r, tmin, tmax) < 0)
            return 0;
        tex_leaf_spans(ob, &r->o, &r->d, s);
    } else if (!ob->bounded) {
        tex_object_spans(ob, r->o, r->d, s);
    } else {
        if (!hit_box(&ob->wb, r, tmin, tmax, &t0))
            return 0;
        tex_csg_spans(ob, &r->o, &r->d, &r->inv, s);
    }
    return 1;
}

/* Spans of a CSG tree or a transformed leaf: the first boundary beyond tmin
 * and before *tmax.  Out of line: the interval lists are large. */
static __attribute__((noinline)) int first_hit_spans(const struct prim *p,
                                                     const struct tex_bvh_ray *r,
                                                     double tmin, double *tmax,
                                                     struct tex_hit *hit)
{
    struct tex_spans s;
    if (!prim_spans(p, r, tmin, *tmax, &s))
        return 0;
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

/* Where ray r first meets p beyond tmin, where p is a sphere or a plane (no t beyond tmin:
 * NaN or a t <= tmin) */
static inline double quick_t(const struct prim *p, const struct tex_bvh_ray *r, double tmin)
{
    double t;
    if (p->kind == PK_SPHERE) {
        tex_v3 oc = tex_v3_sub(r->o, p->a);
        double b = tex_v3_dot(oc, r->d), c = tex_v3_dot(oc, oc) - p->b;
        double disc = b * b - r->dd * c;
        if (disc <= 0)
            return NAN;
        double q = sqrt(disc);
        t = (-b - q) * r->idd; /* no division after the square root */
        if (!(t > tmin))
            t = (-b + q) * r->idd;
        return t;
    }
    double dy = tex_v3_dot(p->a, r->d);
    if (dy == 0)
        return NAN;
    return -(tex_v3_dot(p->a, r->o) + p->b) / dy;
}

/* The first boundary of p beyond tmin and before *tmax: 1, *hit and *tmax updated. */
static inline int first_hit(const struct prim *p, const struct tex_bvh_ray *r, double tmin,
                            double *tmax, struct tex_hit *hit)
{
    if (p->kind != PK_SPHERE && p->kind != PK_PLANE)
        return first_hit_spans(p, r, tmin, tmax, hit);
    double t = quick_t(p, r, tmin);
    if (t > tmin && t < *tmax) {
        hit->t = t;
        hit->leaf = p->ob;
        hit->flip = 0;
        *tmax = t;
        return 1;
    }
    return 0;
}

/* Whether object i (in tree order) is in visit (tex_view_objects) */
static inline int seen(uint64_t visit, int i)
{
    return visit >> (i < TEX_VIEW_OBJECTS ? i : TEX_VIEW_OBJECTS) & 1;
}

/* The children of quad q that r enters within tmin..tmax (bit c: child c), at distances t[c] */
static inline __attribute__((always_inline)) int quad_children(const struct quad *q,
                                                               const struct tex_bvh_ray *r,
                                                               double tmin, double tmax,
                                                               double t[4])
{
#ifdef TEX_X86 /* four boxes in SSE2's lanes, which every x86-64 has: the same answers */
    return tex_box4_sse2(&q->b, &r->o, &r->inv, tmin, tmax, t) & q->mask;
#else
    return tex_box4_hit(&q->b, &r->o, &r->inv, tmin, tmax, t) & q->mask;
#endif
}

/* The children entered (bit c: child c) into lane[], nearer first by t (a tie: the tree's
 * order); returns how many */
static inline int nearer_first(int entered, const double t[4], int lane[4])
{
    int k = 0;
    for (; entered; entered &= entered - 1) {
        int c = __builtin_ctz(entered), j = k++;
        for (; j > 0 && t[lane[j - 1]] > t[c]; j--)
            lane[j] = lane[j - 1];
        lane[j] = c;
    }
    return k;
}

/* Inlined into the entry points: the closest-hit one loses every test of any; tree = 0 (a
 * ray known to miss the tree's box) tests the unbounded objects alone, which need neither
 * 1/d nor 1/d.d. */
static inline __attribute__((always_inline)) int bvh_trace(const struct tex_bvh *t,
                                                           const tex_v3 *o, const tex_v3 *d,
                                                           double tmin, double tmax, int any,
                                                           int tree, uint64_t visit,
                                                           const struct tex_object *from,
                                                           struct tex_hit *hit)
{
    struct tex_bvh_ray r;
    if (tree) {
        ray_setup(&r, o, d);
    } else {
        /* the unbounded read neither inv nor idd */
        r = (struct tex_bvh_ray){*o, *d, {0, 0, 0}, tex_v3_dot(*d, *d), 0};
    }
    int found = 0;
    if (!(r.dd > 0))
        return 0;
    for (int i = 0; i < t->nunb; i++) {
        if (t->unb[i].ob == from)
            continue;
        found |= first_hit(&t->unb[i], &r, tmin, &tmax, hit);
        if (found && any)
            return 1;
    }
    if (!t->nnodes || !tree)
        return found;
    struct ref {
        int first, count; /* a leaf's prims, or (count 0) a quad */
        double t;         /* its entry distance */
    } stack[256], cur;    /* the binary tree is at most SAH_DEPTH + 32 deep: a quad level
                           * folds two of its levels and leaves at most three behind */
    int sp = 0;
    double t0;
    if (!hit_box(&t->nodes[0].b, &r, tmin, tmax, &t0))
        return found;
    cur = (struct ref){t->nodes[0].count ? t->nodes[0].first : 0, t->nodes[0].count, t0};
    for (;;) {
        if (cur.count) {
            const struct prim *p = &t->prims[cur.first];
            for (int i = 0; i < cur.count; i++) {
                if (p[i].ob == from || !seen(visit, cur.first + i))
                    continue;
                found |= first_hit(&p[i], &r, tmin, &tmax, hit);
                if (found && any)
                    return 1;
            }
        } else {
            const struct quad *q = &t->quads[cur.first];
            double tc[4];
            int lane[4], k = nearer_first(quad_children(q, &r, tmin, tmax, tc), tc, lane);
            for (int j = 0; j < k; j++) /* the walk waits on memory: ask for them all now */
                if (!q->count[lane[j]])
                    __builtin_prefetch(&t->quads[q->first[lane[j]]]);
            if (k) {
                /* the farther wait with their entry distances */
                for (int j = k - 1; j > 0; j--)
                    stack[sp++] = (struct ref){q->first[lane[j]], q->count[lane[j]], tc[lane[j]]};
                cur = (struct ref){q->first[lane[0]], q->count[lane[0]], tc[lane[0]]};
                continue;
            }
        }
        /* pop the next node still entered before the closest hit so far */
        for (;;) {
            if (!sp)
                return found;
            sp--;
            if (stack[sp].t <= tmax)
                break;
        }
        cur = stack[sp];
    }
}

int tex_bvh_trace(const struct tex_bvh *t, const tex_v3 *o, const tex_v3 *d, double tmin,
                  double tmax, struct tex_hit *hit)
{
    return bvh_trace(t, o, d, tmin, tmax, 0, 1, ~0ull, NULL, hit);
}

int tex_bvh_trace_any(const struct tex_bvh *t, const tex_v3 *o, const tex_v3 *d, double tmin,
                      double tmax, int any, struct tex_hit *hit)
{
    return any ? bvh_trace(t, o, d, tmin, tmax, 1, 1, ~0ull, NULL, hit)
               : bvh_trace(t, o, d, tmin, tmax, 0, 1, ~0ull, NULL, hit);
}

/* Product of Kt over the boundaries of p in (tmin, tmax) into *tr; 0 at an opaque one. */
static double surface_kt(const struct tex_scene *s, const struct tex_object *leaf)
{
    return (leaf->surface ? leaf->surface : s->surfaces[0])->kt;
}

/* Spans of a CSG tree or a transformed leaf: the product of Kt over its
 * boundaries in (tmin, tmax) into *tr.  Out of line: the interval lists are large. */
static __attribute__((noinline)) void transmit_spans(const struct tex_scene *s,
                                                     const struct prim *p,
                                                     const struct tex_bvh_ray *r,
                                                     double tmin, double tmax, double *tr)
{
    struct tex_spans sp;
    if (p->kind == PK_LEAF) {
        int cross = leaf_segment(p, r, tmin, tmax);
        double kt = surface_kt(s, p->ob);
        if (cross < 0)
            return;
        if (cross > 0 && kt == 0) { /* a crossing of an opaque leaf: the product its spans make */
            *tr *= kt;
            return;
        }
        tex_leaf_spans(p->ob, &r->o, &r->d, &sp);
    } else if (!prim_spans(p, r, tmin, tmax, &sp)) {
        return;
    }
    for (int i = 0; i < sp.n && *tr > 0; i++) {
        const struct tex_hit *h[2] = {&sp.in[i], &sp.out[i]};
        for (int k = 0; k < 2; k++)
            if (h[k]->leaf && h[k]->t > tmin && h[k]->t < tmax)
                *tr *= surface_kt(s, h[k]->leaf);
    }
}

static inline void transmit_prim(const struct tex_scene *s, const struct prim *p,
                                 const struct tex_bvh_ray *r, double tmin, double tmax, double *tr)
{
    double t0, t1;
    int n = 0;
    /* only whether the crossings lie in (tmin, tmax) matters: compare t's
     * numerators with the bounds times the (positive) denominator, no division */
    if (p->kind == PK_SPHERE) {
        tex_v3 oc = tex_v3_sub(r->o, p->a);
        double b = tex_v3_dot(oc, r->d), c = tex_v3_dot(oc, oc) - p->b;
        double disc = b * b - r->dd * c;
        if (disc <= 0)
            return;
        double q = sqrt(disc), lo = tmin * r->dd, hi = tmax * r->dd;
        t0 = -b - q, t1 = -b + q;
        n = (t0 > lo && t0 < hi) + (t1 > lo && t1 < hi);
    } else if (p->kind == PK_PLANE) {
        double dy = tex_v3_dot(p->a, r->d);
        if (dy == 0)
            return;
        double num = -(tex_v3_dot(p->a, r->o) + p->b);
        if (dy < 0)
            num = -num, dy = -dy;
        n = num > tmin * dy && num < tmax * dy;
    } else {
        transmit_spans(s, p, r, tmin, tmax, tr);
        return;
    }
    if (n) {
        double kt = surface_kt(s, p->ob);
        *tr *= n == 2 ? kt * kt : kt;
    }
}

/* Ray i of r (of those in live) through prim p: its product tr[i], and i out of live where
 * the light falls to 1e-4 */
static inline void transmit_rays(const struct tex_scene *s, const struct prim *p,
                                 const struct tex_bvh_ray *r, uint64_t m, const double *tmin,
                                 const double *tmax, const struct tex_object *const *from,
                                 double *tr, uint64_t *live)
{
    for (; m; m &= m - 1) {
        int i = __builtin_ctzll(m);
        if (p->ob == from[i])
            continue;
        transmit_prim(s, p, &r[i], tmin[i], tmax[i], &tr[i]);
        if (tr[i] <= 1e-4)
            tr[i] = 0, *live &= ~(1ull << i);
    }
}

/* The rays of m whose segments enter box b; none where b lies apart from the box around
 * every segment, all (a box widened far beyond the rounding of hit_box's slabs: shadow rays
 * to one light, from a packet's hits, skip most of the tree at one test).  lanes: the rays
 * in vector lanes, eight a vector where wide, else four (NULL: one ray at a time). */
static inline uint64_t rays_box(const struct tex_bounds *b, const struct tex_bvh_ray *r, uint64_t m,
                                const double *tmin, const double *tmax,
                                const struct tex_bounds *all, const struct tex_ray_lanes *lanes,
                                int wide)
{
    if (b->lo.x > all->hi.x || b->hi.x < all->lo.x || b->lo.y > all->hi.y ||
        b->hi.y < all->lo.y || b->lo.z > all->hi.z || b->hi.z < all->lo.z)
        return 0;
#ifdef TEX_X86
    if (lanes && __builtin_popcountll(m) >= 4) /* the rays' lanes, where the CPU has them */
        return wide ? tex_rays_box_avx512(b, lanes, m) : tex_rays_box_avx2(b, lanes, m);
#else
    (void)lanes, (void)wide;
#endif
    uint64_t in = 0;
    double t0;
    for (; m; m &= m - 1) {
        int i = __builtin_ctzll(m);
        in |= (uint64_t)hit_box(b, &r[i], tmin[i], tmax[i], &t0) << i;
    }
    return in;
}

/* b grown to hold p (comparisons, not fmin's call: NaN is caught apart) */
static inline void box_grow(struct tex_bounds *b, tex_v3 p)
{
    b->lo.x = tex_mind(b->lo.x, p.x), b->hi.x = tex_maxd(b->hi.x, p.x);
    b->lo.y = tex_mind(b->lo.y, p.y), b->hi.y = tex_maxd(b->hi.y, p.y);
    b->lo.z = tex_mind(b->lo.z, p.z), b->hi.z = tex_maxd(b->hi.z, p.z);
}

/* The rays walk the tree together, depth first, nearer child first as one ray alone does:
 * each meets the objects it enters in the order its own walk meets them, so that its
 * product of Kt is the one its own walk makes, bit for bit. */
static void transmit_walk(const struct tex_scene *s, int n, struct tex_bvh_ray *r,
                          const double *tmin, const double *tmax,
                          const struct tex_object *const *from, double *tr)
{
    const struct tex_bvh *t = s->bvh;
    /* the box around every segment, widened by a million times the rounding of its ends
     * and of hit_box; the whole space where an end is not finite (a distant light) */
    struct tex_ray_lanes lanes, *lp = NULL; /* the live rays in lanes, eight or more of them */
    int wide = 0; /* one ray's calls (most of them) do not ask the level */
    if (n >= 8 && t->nnodes && tex_simd_level() >= TEX_SIMD_AVX2) {
        lp = &lanes, wide = tex_simd_level() >= TEX_SIMD_AVX512;
        lanes.tmin = tmin, lanes.tmax = tmax;
    }
    struct tex_bounds all = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    double big = 0;
    uint64_t live = 0;
    /* the rays' slabs, the box and the lanes in one pass (the box grown by rays an unbounded
     * object then darkens too: it only has to hold the live ones) */
    for (int i = 0; i < n; i++) {
        ray_slabs(&r[i]);
        tr[i] = 1;
        if (!(r[i].dd > 0))
            continue;
        live |= 1ull << i;
        tex_v3 o = r[i].o, e = tex_v3_madd(o, r[i].d, tmax[i]); /* the far end: the near one is o */
        box_grow(&all, o);
        box_grow(&all, e);
        double size = fabs(e.x) + fabs(e.y) + fabs(e.z) + fabs(o.x) + fabs(o.y) + fabs(o.z);
        big = size < 1e12 ? tex_maxd(big, size) : INFINITY; /* NaN too */
        if (lp) { /* the masks never hold a ray out of live: its lanes go unread */
            lanes.o[0][i] = o.x, lanes.o[1][i] = o.y, lanes.o[2][i] = o.z;
            lanes.inv[0][i] = r[i].inv.x, lanes.inv[1][i] = r[i].inv.y;
            lanes.inv[2][i] = r[i].inv.z;
        }
    }
    for (int i = 0; i < t->nunb && live; i++)
        transmit_rays(s, &t->unb[i], r, live, tmin, tmax, from, tr, &live);
    if (!t->nnodes)
        return;
    if (big < 1e12 && n > 1) { /* one ray: its own test of the box is the same */
        double eps = 1e-9 * (1 + big);
        all.lo = tex_v3_sub(all.lo, tex_v3_make(eps, eps, eps));
        all.hi = tex_v3_add(all.hi, tex_v3_make(eps, eps, eps));
    } else {
        all.lo = tex_v3_make(-INFINITY, -INFINITY, -INFINITY);
        all.hi = tex_v3_make(INFINITY, INFINITY, INFINITY);
    }
    struct {
        int node;
        uint64_t m;
    } stack[128];
    int sp = 0, ni = 0;
    uint64_t m = rays_box(&t->nodes[0].b, r, live, tmin, tmax, &all, lp, wide);
    while (m) {
        const struct node *nd = &t->nodes[ni];
        if (nd->count) {
            for (int i = 0; i < nd->count && (m &= live); i++)
                transmit_rays(s, &t->prims[nd->first + i], r, m, tmin, tmax, from, tr, &live);
        } else {
            int l = ni + 1, rt = nd->first;
            uint64_t ml = rays_box(&t->nodes[l].b, r, m, tmin, tmax, &all, lp, wide);
            uint64_t mr = rays_box(&t->nodes[rt].b, r, m, tmin, tmax, &all, lp, wide);
            if (ml && mr)
                stack[sp].node = rt, stack[sp++].m = mr;
            if (ml || mr) {
                ni = ml ? l : rt, m = ml ? ml : mr;
                continue;
            }
        }
        for (m = 0; !m && sp;) /* the next node some ray still alive enters */
            sp--, ni = stack[sp].node, m = stack[sp].m & live;
    }
}

void tex_scene_transmit_n(const struct tex_scene *s, struct tex_shadow_rays *b)
{
    transmit_walk(s, b->n, b->r, b->tmin, b->tmax, b->from, b->tr);
}

int tex_scene_shadow_batches(const struct tex_scene *s)
{
    return s->bvh->nnodes > 1;
}

double tex_scene_transmit(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                          double tmin, double tmax, const struct tex_object *from)
{
    struct tex_bvh_ray r;
    double tr;
    r.o = *o, r.d = *d;
    transmit_walk(s, 1, &r, &tmin, &tmax, &from, &tr); /* a walk of one ray, specialised */
    return tr;
}

static inline int closest(const struct tex_bvh *t, const tex_v3 *o, const tex_v3 *d, double tmin,
                          double tmax, uint64_t visit, const struct tex_object *from,
                          struct tex_hit *hit)
{
    return bvh_trace(t, o, d, tmin, tmax, 0, 1, visit, from, hit);
}

int tex_scene_trace(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d, double tmin,
                    double tmax, const struct tex_object *from, struct tex_hit *hit)
{
    return closest(s->bvh, o, d, tmin, tmax, ~0ull, from, hit);
}

int tex_scene_trace_unbounded(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                              double tmin, double tmax, struct tex_hit *hit)
{
    return bvh_trace(s->bvh, o, d, tmin, tmax, 0, 0, ~0ull, NULL, hit);
}

int tex_scene_trace_view(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                         uint64_t visit, struct tex_hit *hit)
{
    return closest(s->bvh, o, d, 0, INFINITY, visit, NULL, hit);
}

/* first_hit from 0 for ray i of a packet, which tells the walk where p's boundary lies as
 * far as the closest hit so far (*tmax) too: a tie, bit i of *tie (the order of the objects
 * met decides it), which a nearer hit clears */
static inline int packet_hit(const struct prim *p, const struct tex_bvh_ray *r, double *tmax,
                             struct tex_hit *hit, int i, uint64_t *tie)
{
    double t;
    struct tex_hit h;
    if (p->kind == PK_SPHERE) {
        t = quick_t(p, r, 0);
        h = (struct tex_hit){t, p->ob, 0};
    } else { /* a boundary at *tmax itself is found one step of a double beyond it */
        double far = nextafter(*tmax, INFINITY);
        if (!first_hit_spans(p, r, 0, &far, &h))
            return 0;
        t = h.t;
    }
    if (!(t > 0) || t > *tmax)
        return 0;
    if (t == *tmax) {
        *tie |= 1ull << i;
        return 0;
    }
    *hit = h;
    *tmax = t;
    *tie &= ~(1ull << i);
    return 1;
}

/* The four children of q the rays of m enter (ray lanes l), how they ask (AVX2 or not) */
static inline void packet_children(const struct quad *q, const struct tex_ray_lanes *l,
                                   uint64_t m, uint64_t in[4], double t[4], int avx2)
{
#ifdef TEX_X86
    if (avx2) {
        tex_box4_rays_avx2(&q->b, q->mask, l, m, in, t);
        return;
    }
#endif
    (void)avx2;
    tex_box4_rays(&q->b, q->mask, l, m, in, t);
}

/* A packet's n rays into r and l's lanes (tmin, tmax theirs), each one's hits on the unbounded
 * objects found: the mask of those that enter the tree's box */
static uint64_t packet_start(const struct tex_bvh *t, int n, const tex_ray *rays,
                             struct tex_bvh_ray r[64],
                             struct tex_ray_lanes *l, double tmin[64], double tmax[64],
                             struct tex_hit *hit, int *found)
{
    uint64_t m = 0;
    l->tmin = tmin, l->tmax = tmax;
    for (int k = 0; k < 64; k++) { /* lanes past n: rays that enter nothing, never asked */
        int i = k < n ? k : 0;
        double t0;
        ray_setup(&r[k], &rays[i].o, &rays[i].d);
        tmin[k] = 0, tmax[k] = INFINITY;
        for (int a = 0; a < 3; a++)
            l->o[a][k] = tex_v3_get(r[k].o, a), l->inv[a][k] = tex_v3_get(r[k].inv, a);
        if (k >= n)
            continue;
        found[k] = 0;
        if (!(r[k].dd > 0))
            continue;
        for (int u = 0; u < t->nunb; u++)
            found[k] |= first_hit(&t->unb[u], &r[k], 0, &tmax[k], &hit[k]);
        m |= (uint64_t)hit_box(&t->nodes[0].b, &r[k], 0, tmax[k], &t0) << k;
    }
    return m;
}

int tex_scene_trace_packet(const struct tex_scene *s, int n, const tex_ray *rays, uint64_t visit,
                           struct tex_hit *hit, int *found)
{
    const struct tex_bvh *t = s->bvh;
    if (n > 64 || !t->nquads) { /* a tree of one leaf: each ray's walk is as short */
        for (int k = 0; k < n; k++)
            found[k] = tex_scene_trace_view(s, &rays[k].o, &rays[k].d, visit, &hit[k]);
        return 0;
    }
    struct tex_bvh_ray r[64];
    struct tex_ray_lanes l;
    double tmin[64], tmax[64];
    uint64_t tie = 0, m = packet_start(t, n, rays, r, &l, tmin, tmax, hit, found);
    int avx2 = tex_simd_level() >= TEX_SIMD_AVX2;
    struct {
        int first, count;
        uint64_t m;
        double t; /* the nearest of its rays' entries */
    } stack[256], cur = {0, 0, m, 0};
    int sp = 0;
    while (cur.m) {
        if (cur.count) {
            const struct prim *p = &t->prims[cur.first];
            for (int j = 0; j < cur.count; j++) {
                if (!seen(visit, cur.first + j))
                    continue;
                for (uint64_t b = cur.m; b; b &= b - 1) {
                    int k = __builtin_ctzll(b);
                    found[k] |= packet_hit(&p[j], &r[k], &tmax[k], &hit[k], k, &tie);
                }
            }
        } else {
            const struct quad *q = &t->quads[cur.first];
            uint64_t in[4];
            double tc[4];
            int lane[4];
            packet_children(q, &l, cur.m, in, tc, avx2);
            /* nearer first for the nearest of the rays */
            int k = nearer_first((in[0] != 0) | (in[1] != 0) << 1 | (in[2] != 0) << 2 | (in[3] != 0) << 3,
                                 tc, lane);
            if (k) {
                for (int j = k - 1; j > 0; j--) {
                    int c = lane[j];
                    stack[sp].first = q->first[c], stack[sp].count = q->count[c];
                    stack[sp].m = in[c], stack[sp++].t = tc[c];
                }
                cur.first = q->first[lane[0]], cur.count = q->count[lane[0]], cur.m = in[lane[0]];
                continue;
            }
        }
        /* the next node a ray enters before its closest hit so far: the others' own walks
         * pass it by */
        for (cur.m = 0; !cur.m && sp;) {
            cur = stack[--sp];
            for (uint64_t b = cur.m; b; b &= b - 1)
                if (tmax[__builtin_ctzll(b)] < cur.t)
                    cur.m &= ~(1ull << __builtin_ctzll(b));
        }
    }
    /* a tie: the ray's own walk, whose order of the objects decides it */
    for (uint64_t b = tie; b; b &= b - 1) {
        int k = __builtin_ctzll(b);
        found[k] = tex_scene_trace_view(s, &rays[k].o, &rays[k].d, visit, &hit[k]);
    }
    return __builtin_popcountll(tie);
}

/* Box b's rect r as seen from c in the frame u, v, w (tex_scene_view's): 1, or 0 where
 * it is not wholly ahead */
static int box_view(const struct tex_bounds *b, tex_v3 c, tex_v3 u, tex_v3 v, tex_v3 w,
                    double r[4])
{
    double big = 0;
    r[0] = r[2] = INFINITY, r[1] = r[3] = -INFINITY;
    for (int i = 0; i < 8; i++) { /* a convex box wholly ahead projects inside its corners' */
        tex_v3 p = tex_v3_make(i & 1 ? b->hi.x : b->lo.x, i & 2 ? b->hi.y : b->lo.y,
                               i & 4 ? b->hi.z : b->lo.z);
        tex_v3 q = tex_v3_sub(p, c);
        double z = tex_v3_dot(q, w), a = tex_v3_dot(q, u) / z, e = tex_v3_dot(q, v) / z;
        if (!(z > 0) || !isfinite(a) || !isfinite(e))
            return 0;
        r[0] = tex_mind(r[0], a), r[1] = tex_maxd(r[1], a);
        r[2] = tex_mind(r[2], e), r[3] = tex_maxd(r[3], e);
        big = tex_maxd(big, tex_maxd(fabs(a), fabs(e)));
    }
    /* rounding in the rays and the projections is near 1e-15 (1 + |a|): far inside this */
    double m = 1e-9 * (1 + big);
    r[0] -= m, r[1] += m, r[2] -= m, r[3] += m;
    return 1;
}

int tex_scene_view(const struct tex_scene *s, tex_v3 c, tex_v3 u, tex_v3 v, tex_v3 w,
                   struct tex_view *vw)
{
    const struct tex_bvh *t = s->bvh;
    vw->n = vw->more = 0;
    if (!t || !t->nnodes || !box_view(&t->nodes[0].b, c, u, v, w, vw->rect))
        return 0;
    vw->n = t->nprims < TEX_VIEW_OBJECTS ? t->nprims : TEX_VIEW_OBJECTS;
    vw->more = t->nprims > vw->n;
    for (int i = 0; i < vw->n; i++) {
        double *r = vw->object[i];
        if (!box_view(&t->prims[i].box, c, u, v, w, r)) /* not wholly ahead: everywhere */
            r[0] = r[2] = -INFINITY, r[1] = r[3] = INFINITY;
    }
    return 1;
}

/* Do rects a and b overlap? */
static inline int rects_meet(const double a[4], const double b[4])
{
    return a[1] >= b[0] && a[0] <= b[1] && a[3] >= b[2] && a[2] <= b[3];
}

uint64_t tex_view_objects(const struct tex_view *vw, const double r[4])
{
    if (!rects_meet(r, vw->rect))
        return 0;
    uint64_t visit = vw->more ? 1ull << TEX_VIEW_OBJECTS : 0; /* those past the first n */
    for (int i = 0; i < vw->n; i++)
        visit |= (uint64_t)rects_meet(r, vw->object[i]) << i;
    return visit;
}

/* ---- CSG blocks balanced ---------------------------------------------------------- */

/* A node joining a block's children by op (no transform or surface of its own) */
static struct tex_object *cluster_node(enum tex_csg_op op, int line, int col, tex_csg_alloc alloc,
                                       void *ctx)
{
    struct tex_object *ob = alloc(ctx, sizeof *ob);
    ob->op = op;
    ob->cluster = 1;
    ob->line = line;
    ob->col = col;
    tex_xform_identity(&ob->to_world);
    return ob;
}

struct tex_object *tex_csg_balanced(enum tex_csg_op op, struct tex_object **kids, int n, int line,
                                    int col, tex_csg_alloc alloc, void *ctx)
{
    if (n == 1)
        return kids[0];
    struct tex_object *ob = cluster_node(op, line, col, alloc, ctx);
    ob->a = tex_csg_balanced(op, kids, n / 2, line, col, alloc, ctx);
    ob->b = tex_csg_balanced(op, kids + n / 2, n - n / 2, line, col, alloc, ctx);
    return ob;
}

/* Once the world transforms are known (the scene's set_world), the children of a union or an
 * intersection are joined again by median splits of their boxes' centres along the
 * longest axis: a union of many disjoint objects then culls whole halves by their boxes,
 * as the scene's BVH does for separate objects. */

struct operand {
    struct tex_object *ob;
    double key;
};

static int by_key(const void *a, const void *b)
{
    double x = ((const struct operand *)a)->key, y = ((const struct operand *)b)->key;
    return x < y ? -1 : x > y;
}

/* The operands under a cluster (nodes tex_csg_balanced made), into v. */
static void gather(struct tex_object *ob, struct operand *v, int *n)
{
    if (!ob->cluster) {
        v[(*n)++].ob = ob;
        return;
    }
    gather(ob->a, v, n);
    gather(ob->b, v, n);
}

static int count(const struct tex_object *ob)
{
    return ob->cluster ? count(ob->a) + count(ob->b) : 1;
}

static tex_v3 centre_of(const struct tex_object *ob)
{
    if (!ob->bounded)
        return tex_v3_make(0, 0, 0);
    return tex_v3_scale(tex_v3_add(ob->wb.lo, ob->wb.hi), 0.5);
}

/* v[0..n) joined by op, split at the median of the centres along their longest axis. */
static struct tex_object *spatial(enum tex_csg_op op, struct operand *v, int n,
                                  const struct tex_object *like, tex_csg_alloc alloc, void *ctx)
{
    if (n == 1)
        return v[0].ob;
    tex_v3 lo = centre_of(v[0].ob), hi = lo;
    for (int i = 1; i < n; i++) {
        tex_v3 c = centre_of(v[i].ob);
        lo = tex_v3_min(lo, c), hi = tex_v3_max(hi, c);
    }
    tex_v3 e = tex_v3_sub(hi, lo);
    int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    for (int i = 0; i < n; i++)
        v[i].key = tex_v3_get(centre_of(v[i].ob), axis);
    qsort(v, (size_t)n, sizeof *v, by_key);
    struct tex_object *node = cluster_node(op, like->line, like->col, alloc, ctx);
    node->root = like->root;
    node->a = spatial(op, v, n / 2, like, alloc, ctx);
    node->b = spatial(op, v + n / 2, n - n / 2, like, alloc, ctx);
    return node;
}

/* tex_csg_spatial of the operands under a cluster */
static int operands_spatial(struct tex_object *ob, tex_csg_alloc alloc, void *ctx)
{
    if (!ob->cluster)
        return tex_csg_spatial(ob, alloc, ctx);
    return operands_spatial(ob->a, alloc, ctx) < 0 ? -1 : operands_spatial(ob->b, alloc, ctx);
}

int tex_csg_spatial(struct tex_object *ob, tex_csg_alloc alloc, void *ctx)
{
    if (ob->op == TEX_CSG_LEAF)
        return 0;
    int whole = ob->op != TEX_CSG_DIFFERENCE;
    if ((whole && (ob->a->cluster || ob->b->cluster)) || (!whole && ob->b->cluster)) {
        int n = (whole ? count(ob->a) : 0) + count(ob->b), k = 0;
        struct operand *v = malloc((size_t)n * sizeof *v);
        if (!v)
            return tex_error("out of memory");
        if (whole)
            gather(ob->a, v, &k);
        gather(ob->b, v, &k);
        for (int i = 0; i < n; i++)
            tex_object_bounds(v[i].ob);
        struct tex_object *t = spatial(whole ? ob->op : TEX_CSG_UNION, v, n, ob, alloc, ctx);
        free(v);
        if (whole)
            ob->a = t->a, ob->b = t->b;
        else
            ob->b = t;
    }
    return operands_spatial(ob->a, alloc, ctx) < 0 ? -1 : operands_spatial(ob->b, alloc, ctx);
}
