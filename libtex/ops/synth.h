/* synth.h - texture synthesis from an example (a sample map)
 *
 * Grows a map of any size that looks like a small sample, by
 * multi-resolution neighbourhood matching (Wei and Levoy 2000) in the
 * parallel form of Lefebvre and Hoppe 2005, with k-coherence candidates
 * (Ashikhmin 2001; Tong et al. 2002) found by FLANN.
 *
 *   struct tex_synth_opts o = TEX_SYNTH_DEFAULTS;
 *   o.tile = 1; o.seed = 7;
 *   tex_map *m = tex_synth(sample, 512, 512, &o, NULL, NULL);  // NULL + tex_errmsg()
 *
 * Method.  The synthesis works on coordinates: every output pixel holds
 * the position in the sample that it copies, so the output's values are
 * the sample's own (its histogram is kept).  The sample is turned into a
 * Gaussian stack E_0..E_{L-1} (E_l blurred at 2^l pixels, all of full
 * size); level l compares n x n neighbourhoods whose points lie h = 2^l
 * pixels apart.  Per level, coarsest first:
 *   - candidates: each sample pixel's neighbourhood vector (n^2 values per
 *     channel, weighted by a Gaussian) is reduced by PCA to at most 10
 *     dimensions; FLANN's single kd-tree (searched with eps = 1; it draws
 *     no random numbers) gives each sample pixel its k most similar pixels
 *     (itself first, none closer than h/2).  These k-coherence sets are
 *     built once per level.
 *   - the coarsest level starts as a quilt (Efros and Freeman 2001): blocks
 *     of sample windows, each drawn by the seed among the windows whose
 *     edges best continue the blocks placed before (across the wrap-around
 *     edges too with tile), so regular samples keep their period; a finer
 *     level inherits its parent's position plus h times the child's offset
 *     (upsampling), plus a jitter of up to 2 h randomness pixels.
 *   - correction passes: each output pixel p gathers its neighbourhood
 *     (the stack's values at the positions its neighbours hold) and takes,
 *     of the candidates C_k(S[p+d]) - h d of its 3 x 3 neighbours d and its
 *     own position, the one whose sample neighbourhood is nearest (sum of
 *     squared differences plus an occurrence penalty, after Kaspar et al.
 *     2015: a cell of 8 x 8 sample pixels used more than its share costs
 *     more, which keeps the output's histogram near the sample's; ties keep
 *     the first).  At the coarsest level's first pass the FLANN tree also
 *     proposes the k nearest sample neighbourhoods of the output's own
 *     (projected) neighbourhood, as Wei and Levoy's full search would.  A
 *     pass is 4 subpasses over the 2 x 2 interleaved pixels; every pixel of
 *     a subpass reads the state before it, so any number of threads gives
 *     the same bytes.
 * A candidate keeps half its level's neighbourhood (at least n/2 pixels)
 * inside the sample, the rest read in a mirror of its edges; with a mask,
 * no candidate's neighbourhood touches the (blurred) mask.  When no
 * position fits at some level, fewer levels are used (none fitting even at
 * level 0 is an error: the sample is smaller than the neighbourhood).
 *
 * Options (struct tex_synth_opts):
 *   neighbourhood  n, odd, 3..15 (5): side of the square neighbourhood
 *   levels         1..10 (4): most pyramid levels
 *   k              1..16 (4): candidates per sample pixel
 *   passes         1..8 (2): correction passes per level
 *   randomness     0..1 (0.1): jitter, in units of 2 h
 *   tile           output neighbourhoods wrap around the output (a torus),
 *                  so the map tiles without a seam
 *   seed           the random choices (start and jitter), hashed per pixel
 *   guide_weight   0..100 (0.2): weight of the guide term
 *   search         TEX_SYNTH_COHERENT, or TEX_SYNTH_EXHAUSTIVE: every valid
 *                  sample position is a candidate for every pixel (Wei and
 *                  Levoy's full search, the slow reference)
 *   progress       progress(done, total, arg) after each subpass, or NULL
 *
 * guide (optional, w x h, channel 0 or the luma of RGB): the output
 * follows it: the guide, rank-matched to the distribution of the
 * sample's blurred luma, is compared with that luma at each candidate
 * (guide_weight times the neighbourhood's weight), and two candidates per
 * pixel come from sample positions of similar luma.
 * mask (optional, the sample's size, channel 0 > 0.5 = to fill): the
 * result is the sample with the masked pixels synthesised from the rest
 * (inpainting); w and h are ignored.
 *
 * Errors: a sample of 1 x 1 or smaller than the neighbourhood, NaN or
 * infinity in the sample, a guide or mask of the wrong size, an output
 * over TEX_SYNTH_MAX_PIXELS, a bad option (usage errors, exit 2).
 */
#ifndef TEX_SYNTH_H
#define TEX_SYNTH_H

#include <stdint.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

/* 16384^2: the coordinates and neighbourhoods take about 16 bytes a pixel. */
#define TEX_SYNTH_MAX_PIXELS (1LL << 28)

enum tex_synth_search { TEX_SYNTH_COHERENT, TEX_SYNTH_EXHAUSTIVE };

struct tex_synth_opts {
    int neighbourhood, levels, k, passes;
    double randomness, guide_weight;
    int tile;
    uint64_t seed;
    enum tex_synth_search search;
    /* called from the calling thread after each subpass (may be NULL):
     * done of total pixel updates, over every level and pass */
    void (*progress)(long done, long total, void *arg);
    void *progress_arg;
};

#define TEX_SYNTH_DEFAULTS {5, 4, 4, 2, 0.1, 0.2, 0, 0, TEX_SYNTH_COHERENT, NULL, NULL}

tex_map *tex_synth(const tex_map *sample, int w, int h, const struct tex_synth_opts *o,
                   const tex_map *guide, const tex_map *mask);

TEX_API_END
#endif
