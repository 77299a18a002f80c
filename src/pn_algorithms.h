/* pn_algorithms.h - the registry: every algorithm once, in pn_algo order. From this list
 * come the frame's dispatch and option checks and the scene upload (src/pn_frame.c), the
 * limit checks, the size query and the persistent carve (src/pn_arena.c), the scene work
 * (src/pn_scene.c), pn_build_info() and pn_algo_name() (src/pn_context.c), and CMake's
 * PN_ALGORITHMS names (CMakeLists.txt reads the X lines). Adding an algorithm is its
 * module and one line here (docs/architecture.md, "Adding an algorithm").
 *
 *   X(ID, name)   ID: as in PN_ALGO_<ID>, PN_ENABLE_<ID> and PN_BUILD_<ID>;
 *                 name: its module src/pn_<name>.c, and what pn_algo_name() returns
 *
 * A module provides, whatever the configuration (PN_ALGO_STUBS when PN_ENABLE_<ID> is 0):
 *   pn_<name>_prepare(fs, opt)  checks the algorithm's own options (pn_fail naming the
 *                               option) and derives the frame's parameters from them (fs
 *                               and fs->K; 0 means the default), before any pool is carved;
 *   pn_<name>_limits_ok(l)      whether its own pn_limits fields are in range (1) or not
 *                               (0: pn_arena_size and pn_init fail PN_E_LIMIT);
 *   pn_<name>_query(c, l)       its frame pools' size query: the carve its frame runs
 *                               (pn_internal.h pn_carver), run at the limits' maxima;
 *                               pn_carve sizes the frame region for the largest set;
 *   pn_<name>_persist(c, l)     its persistent pools (carved after the scene's for a context
 *                               that runs it; c a query or the arena, pn_carver_at at
 *                               ctx->layout.algo[ID]);
 *   pn_<name>_scene_scratch(l)  bytes of the frame region its pn_scene_set work uses;
 *   pn_<name>_scene(ctx)        its work at pn_scene_set and pn_scene_update_positions,
 *                               after the BVH (a context that runs it);
 *   pn_<name>_upload(fs)        its persistent pools to the frame's port when the scene
 *                               changed (a context that runs it);
 *   PN_ALGO_NO_SCENE(name) defines the last four for a module with no scene state, and
 *   PN_ALGO_NO_POOLS(name) limits_ok and query for one with no limits and no frame pools;
 *   pn_<name>_frame(fs)         its shadow pass: the visibility buffer and one
 *                               pn_row_counters per row, through the port commands of
 *                               src/pn_device.h. Not internal to this header. */
#ifndef PN_ALGORITHMS_H
#define PN_ALGORITHMS_H

#include "pn_internal.h"

#define PN_ALGORITHMS(X)                                                                       \
    X(REFERENCE, reference)                                                                    \
    X(GEARS, gears)                                                                            \
    X(RAYTRACE, raytrace)                                                                      \
    X(SRT, srt)                                                                                \
    X(OCCTEX, occtex)                                                                          \
    X(MCSM, mcsm)                                                                              \
    X(WEDGES, wedges)

#define PN_ALGO_DECLARE(ID, name)                                                              \
    pn_status pn_##name##_prepare(pn_frame_state *fs, const pn_frame_options *opt);             \
    int pn_##name##_limits_ok(const pn_limits *l);                                              \
    void pn_##name##_query(pn_carver *c, const pn_limits *l);                                   \
    void pn_##name##_persist(pn_carver *c, const pn_limits *l);                                 \
    uint64_t pn_##name##_scene_scratch(const pn_limits *l);                                     \
    pn_status pn_##name##_scene(pn_context *ctx);                                               \
    pn_status pn_##name##_upload(pn_frame_state *fs);                                           \
    pn_status pn_##name##_frame(pn_frame_state *fs);
PN_ALGORITHMS(PN_ALGO_DECLARE)
#undef PN_ALGO_DECLARE

/* The limit check and size query of a module with no limits and no frame pools. */
#define PN_ALGO_NO_POOLS(name)                                                                 \
    int pn_##name##_limits_ok(const pn_limits *l)                                              \
    {                                                                                          \
        (void)l;                                                                               \
        return 1;                                                                              \
    }                                                                                          \
    void pn_##name##_query(pn_carver *c, const pn_limits *l)                                    \
    {                                                                                          \
        (void)c;                                                                               \
        (void)l;                                                                               \
    }

/* The scene hooks of a module that keeps nothing of the scene. */
#define PN_ALGO_NO_SCENE(name)                                                                 \
    void pn_##name##_persist(pn_carver *c, const pn_limits *l)                                  \
    {                                                                                          \
        (void)c;                                                                               \
        (void)l;                                                                               \
    }                                                                                          \
    uint64_t pn_##name##_scene_scratch(const pn_limits *l)                                      \
    {                                                                                          \
        (void)l;                                                                               \
        return 0u;                                                                             \
    }                                                                                          \
    pn_status pn_##name##_scene(pn_context *ctx)                                               \
    {                                                                                          \
        (void)ctx;                                                                             \
        return PN_OK;                                                                          \
    }                                                                                          \
    pn_status pn_##name##_upload(pn_frame_state *fs)                                           \
    {                                                                                          \
        (void)fs;                                                                              \
        return PN_OK;                                                                          \
    }

/* The module of an algorithm that is not compiled in: its prepare refuses every frame; it
 * has no pools and ignores its limits. */
#define PN_ALGO_STUBS(ID, name)                                                                \
    pn_status pn_##name##_prepare(pn_frame_state *fs, const pn_frame_options *opt)             \
    {                                                                                          \
        (void)opt;                                                                             \
        return pn_fail(fs->ctx, PN_E_UNSUPPORTED,                                              \
                       "PN_ALGO_" #ID " is not compiled in (PN_ENABLE_" #ID " 0)");             \
    }                                                                                          \
    PN_ALGO_NO_POOLS(name)                                                                     \
    PN_ALGO_NO_SCENE(name)                                                                     \
    pn_status pn_##name##_frame(pn_frame_state *fs)                                            \
    {                                                                                          \
        (void)fs;                                                                              \
        return PN_E_UNSUPPORTED;                                                               \
    }

/* Each ID's position in the list is its pn_algo value, and its build flag that value's bit
 * (checked at compile time). */
#define PN_ALGO_INDEX(ID, name) PN_ALGO_INDEX_##ID,
enum { PN_ALGORITHMS(PN_ALGO_INDEX) PN_ALGO_LISTED };
#undef PN_ALGO_INDEX
#define PN_ALGO_CHECK(ID, name)                                                                \
    typedef char pn_algo_check_##name[PN_ALGO_INDEX_##ID == (int)PN_ALGO_##ID &&                \
                                      PN_BUILD_##ID == 1u << PN_ALGO_##ID ? 1 : -1];
PN_ALGORITHMS(PN_ALGO_CHECK)
#undef PN_ALGO_CHECK
typedef char pn_algo_check_count[PN_ALGO_LISTED == PN_ALGO_COUNT ? 1 : -1];

#endif
