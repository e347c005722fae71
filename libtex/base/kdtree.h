/* kdtree.h - nearest neighbours in a point set: FLANN's single kd-tree
 *
 * A k-d tree over n points of dim coordinates (row-major, float or double),
 * Euclidean distance, built and searched by FLANN's KDTreeSingleIndex (the
 * index FLANN_INDEX_KDTREE_SINGLE of its C API, which gives the same
 * neighbours).  Distances are squared.  Searches are read-only and safe from
 * many threads at once.
 *
 *   tex_kdtree *t = tex_kdtree_new_d(pts, n, 3, 8);  // NULL and tex_errmsg() on failure
 *   tex_kdtree_knn_d(t, q, nq, k, 0, 1, ind, d2);    // k nearest of each query, nearest first
 *   tex_kdtree_free(t);
 *
 * eps > 0 searches (1 + eps)-approximately: a neighbour returned may be up
 * to 1 + eps times farther than the true one.  sorted asks for the nearest
 * first where FLANN would otherwise leave them unordered.
 *
 * Only these instantiations of FLANN's templates are built, in kdtree.cpp,
 * rather than its C API's library, which holds every index and distance for
 * every type: its relocations and its C++ start-up cost every tool page
 * faults and CPU before main.
 */
#ifndef TEX_KDTREE_H
#define TEX_KDTREE_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tex_kdtree tex_kdtree;

/* The tree of n points pts, which must outlive it, at most leaf points a leaf. */
tex_kdtree *tex_kdtree_new_f(const float *pts, long n, int dim, int leaf);
tex_kdtree *tex_kdtree_new_d(const double *pts, long n, int dim, int leaf);

/* The k nearest points of each of nq queries q (nq x dim) into ind and d2 (nq x k): 0, or
 * -1 with the error set.  The tree must be of the same type. */
int tex_kdtree_knn_f(const tex_kdtree *t, const float *q, int nq, int k, float eps, int sorted,
                     int *ind, float *d2);
int tex_kdtree_knn_d(const tex_kdtree *t, const double *q, int nq, int k, float eps, int sorted,
                     int *ind, double *d2);

/* The points within squared distance r2 of q, in no order, at most max of them into ind and
 * d2: how many there are up to max, or -1 with the error set. */
int tex_kdtree_radius_d(const tex_kdtree *t, const double *q, float r2, int max, int *ind,
                        double *d2);

void tex_kdtree_free(tex_kdtree *t);

#ifdef __cplusplus
}
#endif

#endif
