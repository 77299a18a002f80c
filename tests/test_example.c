/* The usage example of penumbra.h and README.md, as written there, compiles and runs. */
#include <stdio.h>
#include <stdlib.h>

#include "penumbra/penumbra.h"
#include "pn_test.h"

int main(void)
{
    /* A unit square occluder at y = 1 over a floor at y = 0. */
    static const float positions[] = {-0.5f, 1, -0.5f, 0.5f, 1, -0.5f, 0.5f, 1, 0.5f, -0.5f, 1, 0.5f,
                                      -4, 0, -4,       4, 0, -4,       4, 0, 4,       -4, 0, 4};
    static const uint32_t indices[] = {0, 2, 1, 0, 3, 2, 4, 6, 5, 4, 7, 6};
    const uint32_t vertex_count = 8, triangle_count = 4;
    void *memory;
    size_t i, dark = 0;

    /* ---- the example ---- */
    pn_limits lim = { 100000, 512, 512, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    size_t bytes; pn_arena_size(&lim, &bytes);
    memory = malloc(bytes);
    pn_context *ctx; pn_init(&ctx, memory, bytes, &lim);
    pn_scene_set(ctx, positions, vertex_count, indices, triangle_count);
    pn_camera cam = { {0,1,3}, {0,0,0}, {0,1,0}, 45.0f };
    pn_light light = { {0,3,0}, {0.5f,0,0}, {0,0,0.5f} };
    pn_frame_options opt; pn_frame_options_default(&opt);
    pn_frame out;
    if (pn_render(ctx, &cam, &light, &opt, &out) != PN_OK) puts(pn_last_error(ctx));
    /* ---- end of the example ---- */

    CHECK(out.width == 512 && out.height == 512);
    for (i = 0; i < (size_t)out.width * out.height; i++) dark += out.visibility[i] == 0.0f;
    CHECK(dark > 1000); /* the occluder casts an umbra on the floor */
    free(memory);
    return pn_test_summary();
}
