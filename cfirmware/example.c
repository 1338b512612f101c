/*
 * The example of docs/c-abi.md, compiled by `make` so that
 * it stays right: a C²PS cap and an EG ring through capdiv.h, float calls.
 */
#include <stddef.h>
#include <stdint.h>

#include "capdiv.h"

#define VALENCE 6
#define LINKS 5
#define STEPS 4

/* capdiv_c2ps_work_len(6, 4) = 17·96 = 1632 floats (6.4 KiB);
   capdiv_c2ps_out_len(6, 4) = 5 + 15·96 = 1445 floats. */
static float work[17 * (VALENCE << STEPS)];
static float out[5 + 15 * (VALENCE << STEPS)];

/* pole: 3 floats; links: links 1..5, VALENCE points x, y, z each, counter-clockwise. */
int32_t c2ps_cap(const float pole[3], const float links[LINKS * VALENCE * 3], float normal[3]) {
    const size_t coords_len = LINKS * VALENCE * 3;
    int32_t n = capdiv_c2ps_refine_f32(pole, links, coords_len, VALENCE, STEPS, 0, work,
                                       sizeof work / sizeof work[0], out,
                                       sizeof out / sizeof out[0]);
    if (n < 0) return n; /* CAPDIV_ERR_* or CAPDIV_BAD_BUFFER: out untouched */
    /* out: N = 96, K = 5, the pole x y z, then links 1..5 of N points x y z:
       link k, point j, coordinate c at out[5 + 3 * (N * (k - 1) + j) + c]. */

    float jet[CAPDIV_JET_LEN];
    int32_t j = capdiv_c2ps_jet_f32(pole, links, coords_len, VALENCE, STEPS, 0, work,
                                    sizeof work / sizeof work[0], jet, CAPDIV_JET_LEN);
    if (j < 0) return j;
    if (j < CAPDIV_JET_LEN) return CAPDIV_ERR_DEGENERATE; /* p0..p5 only */
    /* jet: p0 (the limit point) .. p5, unit normal, Gaussian, mean, principal curvatures. */
    for (int i = 0; i < 3; ++i) normal[i] = jet[18 + i];
    return n;
}

/* An EG cap of valence 5: 3 steps, then the last ring's 3n = 15 bi-4 patches. */
static float ring[225 * 5];

/* nodes: 5 sectors of 6 nodes x, y, z in the order (1,0) (2,0) (1,1) (2,1) (1,2) (2,2). */
int32_t eg_cap(const float center[3], const float nodes[5 * 6 * 3]) {
    return capdiv_eg_ring_f32(center, nodes, 5 * 6 * 3, 3, ring, sizeof ring / sizeof ring[0]);
    /* patch k, control point (i, j), coordinate c at ring[75 * k + 15 * i + 3 * j + c]. */
}
