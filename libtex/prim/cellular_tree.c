/* cellular_tree.c - the adaptive tree of boxes over the unit square, each with the list of
 * points that can be one of the two nearest inside it */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/kdtree.h"
#include "prim/cellular_impl.h"
#include "prim/x86/cellular_x86.h"

/* The adaptive candidate tree (kd-tree search).  FLANN answers per query
 * at about a microsecond; a row of pixels asks it the same question over
 * and over.  So the unit square (cube) is cut once into boxes, each with a
 * complete candidate list: every point (periodic image) that can be one
 * of the two nearest to a query in the box.  Queries then search their
 * box's list exactly as brute force does, point by point.
 *
 * A box B (centre m, half diagonal hd) gets its list from FLANN: the K
 * nearest neighbours of m are all the points closer than the K-th, E.  Let
 * U bound F2 over B: F2(m) (or the second smallest distance among the K)
 * plus lip hd, F2 being lip-Lipschitz.  A point that is one of the two
 * nearest to q in B has d(q) <= F2(q) <= U, so it lies within U / kfac of
 * B in L2 (kfac: the lower norm bound), and within U / kfac + hd of m.
 * While that is below E (and below the tiling margin), the K points hold
 * the list; otherwise B is split and its children ask FLANN.  A box whose
 * list is long is split too, and its children filter their lists from it:
 * the parent's list is complete at the child's centre, so F2 there is exact
 * and the child's bound is no larger than the parent's.  Boxes FLANN cannot
 * settle even small (many coincident points) leave their queries to
 * kdtree_query.  Lists are built in depth-first order, so the tree is the
 * same on every run. */
enum { ACT_CMAX = 400, ACT_RMAX = 8192, ACT_LEAF = 48, ACT_DEPTH = 14 };

/* Lists under construction, one set per depth: coordinates (dim per
 * entry) and point ids; kid holds the 2^dim children's lists of the node
 * being split at the depth above, own a list straight from FLANN. */
struct act_list {
    double *p;
    long *id, cap;
};

struct act_build {
    int rind[ACT_RMAX];
    double rdist[ACT_RMAX];
    long nnode, capnode, nent, capent, budget, nodebudget, work, workbudget;
    struct act_list kid[ACT_DEPTH + 2], own[ACT_DEPTH + 2];
};

static int act_reserve(struct act_list *l, long n, int dim)
{
    if (n > l->cap) {
        int ok = 1;
        l->p = grown(l->p, (size_t)n * dim, sizeof *l->p, &ok);
        l->id = grown(l->id, n, sizeof *l->id, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate tree");
        l->cap = n;
    }
    return 0;
}

static int act_grow(struct tex_cellular *c, struct act_build *B, long nodes, long ents)
{
    if (B->nnode + nodes > B->capnode) {
        long nc = 2 * (B->nnode + nodes);
        int ok = 1;
        c->achild = grown(c->achild, nc, sizeof *c->achild, &ok);
        c->astart = grown(c->astart, nc, sizeof *c->astart, &ok);
        c->alen = grown(c->alen, nc, sizeof *c->alen, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate tree");
        B->capnode = nc;
    }
    if (B->nent + ents > B->capent) {
        long nc = 2 * (B->nent + ents);
        int ok = 1;
        c->ax = grown(c->ax, nc, sizeof *c->ax, &ok);
        c->ay = grown(c->ay, nc, sizeof *c->ay, &ok);
        c->aid = grown(c->aid, nc, sizeof *c->aid, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate tree");
        B->capent = nc;
    }
    return 0;
}

/* Two smallest squared L2 distances from each of the 2^D child centres to
 * the list (an upper bound only: rounding here is absorbed by the slack). */
static inline __attribute__((always_inline)) void act_f2_euclid(const double *lp, int n,
                                                                const int D, double cm[8][3],
                                                                double *s1, double *s2)
{
    for (int t = 0; t < n; t++) {
        const double *p = lp + (size_t)t * D;
        for (int k = 0; k < 1 << D; k++) {
            double a = 0;
            for (int d = 0; d < D; d++)
                a += (cm[k][d] - p[d]) * (cm[k][d] - p[d]);
            double lo = a < s1[k] ? a : s1[k], hi = a < s1[k] ? s1[k] : a;
            s1[k] = lo;
            s2[k] = hi < s2[k] ? hi : s2[k];
        }
    }
}

/* Each child's list: the entries within sqrt(thr[k]) of its box. */
static inline __attribute__((always_inline)) void
act_filter(const double *lp, const long *lid, int n, const int D, double clo[8][3],
           double chi[8][3], const double *thr, struct act_list *kid, int *cn)
{
    for (int t = 0; t < n; t++) {
        const double *p = lp + (size_t)t * D;
        for (int k = 0; k < 1 << D; k++) {
            double e2 = 0;
            for (int d = 0; d < D; d++) {
                double x = fmax(clo[k][d] - p[d], p[d] - chi[k][d]);
                x = x > 0 ? x : 0;
                e2 += x * x;
            }
            if (e2 <= thr[k]) {
                long at = (long)k * n + cn[k]++;
                for (int d = 0; d < D; d++)
                    kid->p[at * D + d] = p[d];
                kid->id[at] = lid[t];
            }
        }
    }
}

/* What act_gather decided for a node. */
enum { ACT_LISTED, ACT_SPLIT, ACT_DONE, ACT_OVER };

/* F2 at m from its two nearest representatives: the reach R within which
 * every point that may matter in a box of half-diagonal hd lies, F2 itself,
 * and the squared distance to the second nearest. */
static int act_reach(const struct tex_cellular *c, const double *m, double hd,
                     double *R, double *f2, double *d2)
{
    int k2 = c->nrep < 2 ? 1 : 2, ind[2];
    double dist[2], s1 = INFINITY, s2 = INFINITY, zero[3] = {0, 0, 0};
    if (tex_kdtree_knn_d(c->index, m, 1, k2, 0, 0, ind, dist) < 0)
        return -1;
    for (int t = 0; t < k2; t++) {
        long id = c->repid[ind[t]];
        double a = acc_point(c, m, c->rep + (size_t)ind[t] * c->dim,
                             c->ia ? c->ia + id * c->dim : NULL, zero);
        s2 = t == 0 ? INFINITY : a > s1 ? a : s1;
        s1 = t == 0 ? a : a < s1 ? a : s1;
    }
    *f2 = acc_finish(c, s2) / c->kfac;
    *R = ((acc_finish(c, s2) + c->lip * hd) / c->kfac) * (1 + 1e-9) + 1e-12 + hd * (1 + 1e-9);
    *d2 = dist[k2 - 1];
    return 0;
}

/* Keep, in `own`, the n points found around m that lie within the exact
 * reach of the box lo + [0,side)^dim. */
static int act_keep(const struct tex_cellular *c, const struct act_build *B, struct act_list *own,
                    const double *m, const double *lo, double side, double hd, int n)
{
    int dim = c->dim, nl = 0;
    double s1 = INFINITY, s2 = INFINITY, thr, zero[3] = {0, 0, 0};
    for (int t = 0; t < n; t++) {
        long id = c->repid[B->rind[t]];
        double a = acc_point(c, m, c->rep + (size_t)B->rind[t] * dim,
                             c->ia ? c->ia + id * dim : NULL, zero);
        if (a < s1)
            s2 = s1, s1 = a;
        else if (a < s2)
            s2 = a;
    }
    thr = ((acc_finish(c, s2) + c->lip * hd) / c->kfac) * (1 + 1e-9) + 1e-12;
    if (act_reserve(own, n, dim) < 0)
        return -1;
    for (int t = 0; t < n; t++) {
        const double *p = c->rep + (size_t)B->rind[t] * dim;
        double e2 = 0;
        for (int d = 0; d < dim; d++) {
            double x = p[d] < lo[d] ? lo[d] - p[d] : p[d] > lo[d] + side ? p[d] - (lo[d] + side) : 0;
            e2 += x * x;
        }
        if (e2 <= thr * thr) {
            memcpy(own->p + (size_t)nl * dim, p, dim * sizeof *p);
            own->id[nl++] = c->repid[B->rind[t]];
        }
    }
    return nl;
}

/* A node without a list: F2 at its centre, then every point within reach
 * from FLANN, kept in B->own[depth] (*n of them).  Returns ACT_LISTED,
 * ACT_SPLIT (too many points: split without a list), ACT_DONE (the node
 * stays a kd-tree query) or -1. */
static int act_gather(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                      double side, int depth, int *n)
{
    int dim = c->dim, maxnn, got;
    double hd = 0.5 * side * sqrt((double)dim), m[3], R = 0, f2 = 0, d2 = 0, est;
    for (int d = 0; d < dim; d++)
        m[d] = lo[d] + 0.5 * side;
    if (act_reach(c, m, hd, &R, &f2, &d2) < 0)
        return -1;
    if (c->tile && !(R < c->margin * (1 - 1e-9))) {
        /* Images beyond the margin are not in the tree: smaller boxes
         * help while F2 stays well inside it, else kdtree_query. */
        c->achild[node] = -2;
        return f2 < 0.5 * c->margin && depth < ACT_DEPTH ? ACT_SPLIT : ACT_DONE;
    }
    /* Points within R: about 2 (R / |m - second nearest|)^dim. */
    est = R == INFINITY ? (double)c->nrep : 2 * pow(R / fmax(sqrt(d2), 1e-300), dim) + 16;
    if (est > ACT_CMAX && est < c->nrep && depth < ACT_DEPTH) {
        c->achild[node] = -2;
        return ACT_SPLIT;
    }
    maxnn = est < ACT_RMAX ? (int)est + 16 : ACT_RMAX;
    for (;;) {
        float r2 = R == INFINITY ? INFINITY : nextafterf((float)(R * R), INFINITY);
        if (maxnn > c->nrep)
            maxnn = (int)c->nrep + 1;
        if ((B->work += maxnn) > B->workbudget)
            return ACT_OVER;
        got = tex_kdtree_radius_d(c->index, m, r2, maxnn, B->rind, B->rdist);
        if (got < 0)
            return -1;
        if (got < maxnn)
            break; /* all of them */
        if (maxnn < ACT_RMAX) {
            maxnn = 4 * maxnn < ACT_RMAX ? 4 * maxnn : ACT_RMAX;
            continue;
        }
        c->achild[node] = -2;
        return depth < ACT_DEPTH ? ACT_SPLIT : ACT_DONE;
    }
    /* F2 at m is exact now; keep the points within reach of the box. */
    if ((*n = act_keep(c, B, &B->own[depth], m, lo, side, hd, got)) < 0)
        return -1;
    return ACT_LISTED;
}

/* A leaf: its list goes into the flat arrays.  1 when the budget runs out. */
static int act_fill_leaf(struct tex_cellular *c, struct act_build *B, long node, const double *lp,
                         const long *lid, int n)
{
    int dim = c->dim;
    if (B->nent + n > B->budget)
        return 1;
    if (act_grow(c, B, 0, n) < 0)
        return -1;
    c->achild[node] = -1;
    c->astart[node] = B->nent;
    c->alen[node] = n;
    memcpy(c->aid + B->nent, lid, (size_t)n * sizeof *lid);
    for (int t = 0; t < n; t++) {
        c->ax[B->nent + t] = lp[t * dim];
        c->ay[B->nent + t] = lp[t * dim + 1];
    }
    B->nent += n;
    return 0;
}

static int act_node(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                    double side, int depth, const double *lp, const long *lid, int n);

/* Split a node into 2^dim children.  With a complete list, F2 at every
 * child's centre is exact: each child's list keeps the entries within its
 * reach.  Without one, each child gathers its own. */
static int act_split(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                     double side, int depth, const double *lp, const long *lid, int n)
{
    int dim = c->dim, nch = 1 << dim, ret = 0, cn[8] = {0};
    int euclid = c->metric == TEX_METRIC_EUCLID && !c->ia;
    double hd = 0.5 * side * sqrt((double)dim), zero[3] = {0, 0, 0};
    long first = B->nnode;
    struct act_list *kid = &B->kid[depth + 1];
    double clo[8][3], chi[8][3], cm[8][3], s1[8], s2[8], thr[8];
    if (B->nnode + nch > B->nodebudget)
        return 1;
    if (act_grow(c, B, nch, 0) < 0 || (lp && act_reserve(kid, (long)nch * n, dim) < 0))
        return -1;
    B->nnode += nch;
    c->achild[node] = (int)first;
    for (int k = 0; k < nch; k++) {
        for (int d = 0; d < dim; d++) {
            clo[k][d] = lo[d] + ((k >> d) & 1) * 0.5 * side;
            chi[k][d] = clo[k][d] + 0.5 * side;
            cm[k][d] = clo[k][d] + 0.25 * side;
        }
        s1[k] = s2[k] = INFINITY;
    }
    if (lp) {
        if (euclid && dim == 2)
            act_f2_euclid(lp, n, 2, cm, s1, s2);
        else if (euclid)
            act_f2_euclid(lp, n, 3, cm, s1, s2);
        else
            for (int t = 0; t < n; t++)
                for (int k = 0; k < nch; k++) {
                    double a = acc_point(c, cm[k], lp + (size_t)t * dim,
                                         c->ia ? c->ia + lid[t] * dim : NULL, zero);
                    if (a < s1[k])
                        s2[k] = s1[k], s1[k] = a;
                    else if (a < s2[k])
                        s2[k] = a;
                }
        for (int k = 0; k < nch; k++) {
            thr[k] = ((acc_finish(c, s2[k]) + c->lip * 0.5 * hd) / c->kfac) * (1 + 1e-9) + 1e-12;
            thr[k] *= thr[k];
        }
        if (dim == 2)
            act_filter(lp, lid, n, 2, clo, chi, thr, kid, cn);
        else
            act_filter(lp, lid, n, 3, clo, chi, thr, kid, cn);
    }
    for (int k = 0; k < nch && ret == 0; k++)
        ret = act_node(c, B, first + k, clo[k], 0.5 * side, depth + 1,
                       lp ? kid->p + (size_t)k * n * dim : NULL, lp ? kid->id + (size_t)k * n : NULL,
                       cn[k]);
    return ret;
}

/* Fill node `node` (box lo + [0,side)^dim) from its complete list lp, lid
 * (n entries) or, without one, from FLANN.  Returns -1 on failure, 1 when
 * a budget runs out. */
static int act_node(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                    double side, int depth, const double *lp, const long *lid, int n)
{
    if (!lp) {
        int r = act_gather(c, B, node, lo, side, depth, &n);
        if (r < 0)
            return -1;
        if (r == ACT_DONE)
            return 0;
        if (r == ACT_OVER)
            return 1;
        if (r == ACT_SPLIT)
            return act_split(c, B, node, lo, side, depth, NULL, NULL, 0);
        lp = B->own[depth].p;
        lid = B->own[depth].id;
    }
    if (n <= ACT_LEAF || depth >= ACT_DEPTH)
        return act_fill_leaf(c, B, node, lp, lid, n);
    return act_split(c, B, node, lo, side, depth, lp, lid, n);
}

void tex_cellular_tree_free(struct tex_cellular *c)
{
    free(c->achild), free(c->astart), free(c->alen);
    free(c->ax), free(c->ay), free(c->aid);
    c->achild = c->alen = NULL;
    c->astart = c->aid = NULL;
    c->ax = c->ay = NULL;
    c->at = 0;
}

/* Top boxes of about ACT_K / 4 points; an entry budget keeps memory in
 * check (beyond it the queries go to kdtree_query), and a budget of points
 * asked of FLANN keeps time in check: 10^4 points within 10^-12 of one
 * another fill every box to ACT_RMAX down to ACT_DEPTH (over a minute); sets
 * spread as users make them ask about 22 n. */
int tex_cellular_tree_build(struct tex_cellular *c)
{
    int dim = c->dim, T = 1, ret = 0;
    struct act_build *B = calloc(1, sizeof *B);
    long ntop;

    if (!B)
        return tex_error("out of memory for the candidate tree");
    B->budget = 32 * c->n + (1L << 20);
    B->nodebudget = 16 * c->n + (1L << 16);
    B->workbudget = 256 * c->n + (1L << 24);
    while (pow(2.0 * T, dim) <= c->n / 32.0 && T < (dim == 2 ? 1024 : 64))
        T *= 2;
    ntop = dim == 2 ? (long)T * T : (long)T * T * T;
    if (act_grow(c, B, ntop, 0) < 0) {
        free(B);
        return -1;
    }
    B->nnode = ntop;
    c->at = T;
    for (long k = 0; k < ntop && ret == 0; k++) {
        double lo[3] = {(double)(k % T) / T, (double)(k / T % T) / T, (double)(k / T / T) / T};
        ret = act_node(c, B, k, lo, 1.0 / T, 0, NULL, NULL, 0);
    }
    for (int d = 0; d < ACT_DEPTH + 2; d++) {
        free(B->kid[d].p), free(B->kid[d].id);
        free(B->own[d].p), free(B->own[d].id);
    }
    free(B);
    if (ret > 0)
        tex_cellular_tree_free(c); /* over budget: the queries go to kdtree_query */
    return ret < 0 ? -1 : 0;
}

/* The leaf holding q (in [0,1)^dim): its node, box corner lo and side. */
static long act_leaf(const struct tex_cellular *c, const double *q, double *lo, double *side)
{
    int dim = c->dim, T = c->at;
    long node = 0;

    *side = 1.0 / T;
    for (int d = dim - 1; d >= 0; d--) {
        int k = cell_of(q[d], T);
        node = node * T + k;
        lo[d] = (double)k / T;
    }
    while (c->achild[node] >= 0) {
        int k = 0;
        *side *= 0.5;
        for (int d = 0; d < dim; d++)
            if (q[d] >= lo[d] + *side) {
                k |= 1 << d;
                lo[d] += *side;
            }
        node = c->achild[node] + k;
    }
    return node;
}

/* Queries (wrapped, finite) through the tree; b as brute force gives it. */
void tex_cellular_tree_query(const struct tex_cellular *c, int n, const double *q, struct best *b,
                             int want_id, int want_f2)
{
    int dim = c->dim, vec = dim == 2 && c->metric == TEX_METRIC_EUCLID && !c->ia;
    double lo[3] = {0, 0, 0}, side = -1, zero[3] = {0, 0, 0};
    long node = -1;

    for (int i = 0; i < n;) {
        const double *qi = q + (size_t)i * dim;
        int in = 1, inleaf = side > 0, j = i + 1;
        for (int d = 0; d < dim; d++) {
            in &= qi[d] >= 0 && qi[d] < 1;
            inleaf &= qi[d] >= lo[d] && qi[d] < lo[d] + side;
        }
        if (!in) {
            tex_cellular_kdtree_query(c, 1, qi, b + i);
            i = j;
            continue;
        }
        if (!inleaf)
            node = act_leaf(c, qi, lo, &side);
        if (c->achild[node] == -2) {
            tex_cellular_kdtree_query(c, 1, qi, b + i);
            i = j;
            continue;
        }
        long t0 = c->astart[node], e = t0 + c->alen[node];
        if (vec) {
            /* The run of queries in this leaf, up to 16 at a time. */
            for (; j < n && j - i < 16; j++) {
                const double *qj = q + 2 * (size_t)j;
                if (!(qj[0] >= lo[0] && qj[0] < lo[0] + side && qj[1] >= lo[1] &&
                      qj[1] < lo[1] + side))
                    break;
            }
            int m = j - i, nv = (m + 3) / 4;
            double qx[16], qy[16], a1[16], a2[16];
            long i1[16];
            for (int l = 0; l < 4 * nv; l++) {
                qx[l] = q[2 * (size_t)(i + (l < m ? l : 0))];
                qy[l] = q[2 * (size_t)(i + (l < m ? l : 0)) + 1];
            }
#ifdef HAVE_AVX2_KERNEL
            if (c->avx2)
                tex_cellular_lanes_avx2(c->ax, c->ay, c->aid, t0, e, qx, qy, nv, want_id, want_f2,
                                        0, a1, a2, i1);
            else
#endif
                tex_cellular_lanes(c->ax, c->ay, c->aid, t0, e, qx, qy, nv, want_id, want_f2, 0,
                                   a1, a2, i1);
            for (int l = 0; l < m; l++)
                b[i + l].a1 = a1[l], b[i + l].a2 = a2[l], b[i + l].i1 = i1[l];
        } else {
            best_init(b + i);
            for (long t = t0; t < e; t++) {
                long id = c->aid[t];
                double pt[2] = {c->ax[t], c->ay[t]};
                best_add(b + i, acc_point(c, qi, pt, c->ia ? c->ia + id * 2 : NULL, zero), id);
            }
        }
        i = j;
    }
}
