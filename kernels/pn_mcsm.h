/* pn_mcsm.h - Monte Carlo shadow maps (Curtis 2009, "Real-time soft shadows on the GPU via
 * Monte Carlo sampling"): the work items of the frame in src/pn_mcsm.c.
 *
 * Frame of reference. The light frame of pn_lview.h: origin at the light centre c, axes
 * lview's r, u, f (an area light: U^, V^, N), depth z along f. The depth layers are seen
 * from a centre of projection d behind the light centre whose frustum passes through the
 * light's edges and holds every lit shadow-ray origin (pn_lview_window; the thesis' eq. 3.1
 * places the projection point so that "the entire light fits within the view frustum"):
 * then every segment from a point of the light to an origin projects inside that frustum
 * (§3, "every point along the ray projects to a point in the interior of the depth map").
 * The map's window is then narrowed to the image of the occluders' box
 * (pn_lview_fit_occluders): where the receivers reach far beyond the occluders (a ground
 * to the horizon) the thesis' window spends most texels where no occluder is. A point whose
 * image lies beyond the narrowed map lies in no occluder; each ray's search is clipped to
 * the map (pn_mc_clip) and a region reaching beyond it counts those texels empty.
 * A point light has d = 0: its one ray projects to a single texel (a shadow-map test).
 *
 * Layers (§3.3). Over the fragments of every triangle not marked receiver-only
 * (pn_scene_set_receivers; §3.3 requires pure receivers to stay out), in front of the light
 * plane, each texel keeps the nearest depth (near layer) and the farthest of its back
 * faces, those turned away from the centre of projection (far layer), and at least the near
 * depth: the thesis renders the far layer from back faces with the depth test reversed. A
 * texel's occupied interval is [near, far]: the volume between the layers is taken as
 * solid, and a back face is where a solid ends. A surface facing the light with nothing
 * behind it (a floor, a wall of the room the light is in) ends none: were it the far layer,
 * the air between a table and the floor under it would be solid, and rays to the floor
 * beside the table's shadow, whose images cross the table's, would be blocked (the living
 * room's ring of darker penumbra; a room's furniture). A single open sheet stays an occluder
 * of zero thickness (near = far). Empty texels: near = +inf, far = -inf.
 *
 * N-buffer (§3.5; kernels/pn_nbuffer.h). Three channels per texel and level: min near,
 * max far, max near (stored with min near negated, so that every channel is a max:
 * pn_nb_mm_get); level 0 is the layers (max near = near, or +inf for a stacked texel:
 * pn_mc_band, pn_mc_stacked_texel; no region holding one is umbra).
 *
 * Rays (§3, §3.1). Ray i of pixel (x, y) goes from a point S of the light, jittered in cell
 * i of an n x n grid by the reduced 16-step MD5 of Appendix A (pn_md5r, seeded by the pixel
 * coordinates and the ray index, keyed by the frame key), to the pixel's shadow-ray origin
 * E (pn_shadow_origin), pulled back toward S by the adaptive bias of eq. 3.2. On the ray,
 * X(t) = S + t (E - S), its depth is t z_E (S is at depth 0), and its image in the layers is
 * a straight segment. A ray is blocked when
 *   one layer:  some point of it lies at or behind the near layer of its texel;
 *   two layers: some point lies in its texel's [near, far];
 *   three layers: the same, unless that point is seen from the eye (in front of the
 *     G-buffer's depth at its pixel: empty space, Algorithm 1).
 * Its end point counts (the thesis' "endpoint inside a solid object" test, one lookup): the
 * searches walk half-open steps and would miss an end lying exactly on a solid texel's edge.
 * Visibility = unblocked rays / n^2, then the screen-space blur.
 *
 * Early-outs and shortening (§3.6, §3.7), all but the umbra test consistent with the
 * model above: a pixel whose surface, as its winding orients it, faces away from the light
 * centre is umbra (the thesis' first early-out, per fragment; for a closed mesh the exact
 * algorithms' convention gives the same, and the layers cannot show a surface its own back
 * side), and a ray toward a light point behind the surface's plane is blocked (the horizon
 * of invariant 6); a pixel whose origin lies no
 * deeper than the smallest near depth of the region every ray can reach (eq. 3.3, refined
 * twice from the whole map's minimum; pn_mc_reach) is lit; with one or two layers, a pixel
 * whose every ray ends behind the largest near depth of that region is umbra (the thesis'
 * test; with two layers it assumes solid occluders, with three it is off, as the thesis
 * says); a ray whose own region has no near depth before its end is unblocked; rays start
 * at the region's smallest near depth and, with two or more layers, end at its largest far
 * depth. With one layer every one of them gives the model's answer: test_mcsm renders
 * the same bytes with and without them (at 512x512 on thin and the bunny; every built-in
 * and shared scene at 512x512 and 333x257 does too, and at 256x192 all but one bunny
 * pixel, where a ray grazes a near depth by one ulp at a texel's edge and the search's
 * point rounds onto the next texel).
 *
 * Searches. Linear (§3.3): samples one texel apart in the layers' image, each in front of,
 * inside or behind its texel's interval; a change between in front and behind is refined
 * by bisection (PN_MC_BISECT steps), and a bracket that ends within one texel, in front at
 * its start and behind at its end, crossed that texel's interval: blocked. Hierarchical
 * (Algorithm 2): a box of 2^l texels placed at the current point toward the ray's end; if
 * the ray's depths inside the box meet the box's [min near, max far], step to the depth
 * min near and descend (at level 0: blocked), else step past the box and ascend. Every
 * search is capped at PN_MC_STEP_CAP(res) steps (counted; the ray then counts as
 * unblocked). Points whose image lies beyond the map (origins the window had to leave out,
 * beyond PN_LVIEW_TAN_MAX) see no occluder.
 *
 * Blur (§3). A separable filter over the visibility buffer, binomial weights C(2r, r + i)
 * (a Gaussian of variance r / 2 in integers, so no exp), each neighbour's weight divided
 * by 1 + |its depth - the centre's| blur_depth / centre depth (the thesis' depth-sensitive
 * filter, "inversely proportional to the difference ... plus 1", in relative depth);
 * background neighbours, neighbours across a crease (normals more than about 37 degrees
 * apart: the normal sensitivity the thesis recommends) and neighbours across a hard shadow
 * edge (visibility more than PN_MC_BLUR_JUMP from the centre's) take no part. Taps summed
 * in a fixed order.
 *
 * Every float operation is the same on both ports (no contraction, correctly rounded
 * divide and sqrt, integer hashing and exact int-to-float conversions for the samples). */
#ifndef PN_MCSM_H
#define PN_MCSM_H

#include "pn_lview.h"
#include "pn_nbuffer.h"
#include "pn_predicate.h"
#include "pn_raster.h"

#define PN_MC_S_LINEAR 1u
#define PN_MC_S_HIER 2u
#define PN_MC_F_NO_BIAS 1u
#define PN_MC_F_NO_CLASSIFY 2u
#define PN_MC_F_NO_STACKED 4u
#define PN_MC_RAYS_MAX 8u
#define PN_MC_BLUR_MAX 8u
/* Bisection steps of the linear search's refinement (1/256 of a texel). */
#define PN_MC_BISECT 8u
/* Steps one search may take. */
#define PN_MC_STEP_CAP(res) (8u * (res) + 64u)
/* The least cosine of a surface's normal with the direction to the light centre that the
 * adaptive bias serves (eq. 3.2: "n . l must be limited to some small, non-zero value"):
 * below it a texel's depth range on the surface grows faster than any bias that does not
 * leak (as a floor of the bias, measured on the shared scenes at 512x512 against a k = 32
 * reference: 0.25 left grazing surfaces self-shadowed, spot 0.038, bunny 0.035; 0.1 gave spot
 * 0.023, bunny 0.030; 0.05 leaked on chess, CAD and the Buddha). A pixel left in penumbra
 * below it is not searched but marked PN_MC_VIS_OUTSIDE for the exact fallback's pass
 * (pn_stats.mcsm.grazing). 512x512, k = 16 reference, every scene's RMSE as a floor of 0.1
 * without the fallback, with it at 0.1, 0.2 and 0.3: the room 0.0536, 0.0487, 0.0444,
 * 0.0440; the living room 0.0576, 0.0552, 0.0537, 0.0527; the Buddha 0.0323, 0.0285, 0.0257,
 * 0.0245; no scene worse at any; the pixels it sends to the fallback at 0.2 at most 4.5% of
 * the lit ones (the Buddha), the shadow pass 1.0 to 1.56 times as long (the dragon). */
#define PN_MC_COS_MIN 0.2f
/* Relative slack of a depth bound turned into a ray parameter (t = z / z_E): the rounding
 * of t z_E must not move a ray's crossing of a plane occluder (near = far) out of the
 * searched range. */
#define PN_MC_T_SLACK 2.4e-7f
/* The smallest step of the hierarchical search, as a fraction of the searched range (taken
 * only where rounding leaves no exit after the current point). */
#define PN_MC_T_STEP 2.44140625e-4f
/* Texels from a box side, per texel of the map's side, within which a point whose exit rounds
 * to before it is taken to lie on that side: about 20 ulps of the map's size, the rounding of
 * a point's image (1e-2 texels at 4096, 1.6e-4 at 64). Farther in, the exit's own rounding
 * put it before the point: an image that barely moves (a ray nearly along the light view's
 * line of sight), whose exit the search takes as never. As a fixed 1e-2 texels, a point
 * 0.007 texels inside its texel of a 64^2 map was moved to the next one, whose nearer depth
 * then sent the search up and down one level by steps of 2.4e-4 of the ray until its cap,
 * which answered open (fuzz_culls: lit with the classification, blocked without). */
#define PN_MC_ON_EDGE_REL 2.44140625e-6f
/* Neighbours whose normal is more than about 37 degrees off the centre's take no part in
 * its blur. */
#define PN_MC_BLUR_COS 0.8f
/* Neighbours whose visibility differs from the centre's by more than this take no part in
 * its blur: a jump of more than six ninths between neighbouring pixels is a hard shadow
 * edge (a contact shadow, a terminator within one pixel), not the noise of n x n rays, and
 * blurring across it raised an umbra pixel beside lit ones by a quarter or more (gross
 * brighter pixels at 512x512: chess 0.44% -> 0.20%, dragon 0.36% -> 0.15%, buddha 0.27%
 * -> 0.12%). Chosen from data on every scene (0.25, 0.34, 0.5, 0.67, 0.75, 0.84 and no
 * limit: docs/algorithms/mcsm.md). */
#define PN_MC_BLUR_JUMP 0.67f
/* Texels beyond each side of the map that a ray's search still walks (pn_mc_clip): room
 * for the rounding of the clip's parameters (the window is at most 256 times narrower than
 * the light's image, so a relative error of 1e-6 moves an image point by well under one). */
#define PN_MC_CLIP_TEXELS 4.0f
/* Per-row class counters (pool mc_words, PN_MC_WORDS used of PN_MC_ROW_WORDS per row: a
 * row's words fill a cache line of their own, like pn_row_counters). */
#define PN_MC_WORD_LIT 0u
#define PN_MC_WORD_UMBRA 1u
#define PN_MC_WORD_PENUMBRA 2u      /* penumbra pixels whose rays came back mixed */
#define PN_MC_WORD_PENUMBRA_OPEN 3u /* ...that no layer blocked (lit as far as the layers say) */
#define PN_MC_WORD_PENUMBRA_SHUT 4u /* ...whose every sample in front was blocked */
#define PN_MC_WORD_GRAZING 5u        /* ...whose surface the light centre grazes: exact */
#define PN_MC_WORD_CAPPED 6u
#define PN_MC_WORD_STACKED 7u        /* ...whose rays the layers blocked in a stacked texel: exact rays */
#define PN_MC_WORDS 8u
#define PN_MC_ROW_WORDS 16u

/* The parts, in order (each uses those before it). */
#include "pn_mc_hash.h"
#include "pn_mc_layers.h"
#include "pn_mc_search.h"
#include "pn_mc_pixel.h"
#include "pn_mc_blur.h"

#endif
