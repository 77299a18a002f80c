/* consumer.c - a project that uses an installed penumbra: one tiny frame, exit 0 if it rendered. */
#include <stdio.h>
#include <stdlib.h>
#include <penumbra/penumbra.h>

int main(void)
{
    static const float pos[] = {-1, 1, -1, 1, 1, -1, 0, 1, 1, -4, 0, -4, 4, 0, -4, 0, 0, 4};
    static const uint32_t idx[] = {0, 2, 1, 3, 5, 4};
    pn_limits lim = {2, 8, 8, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    size_t bytes;
    pn_context *ctx;
    pn_camera cam = {{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 45.0f};
    pn_light light = {{0, 3, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}};
    pn_frame_options opt;
    pn_frame out;
    void *mem;
    if (pn_arena_size(&lim, &bytes) != PN_OK || !(mem = malloc(bytes))) return 1;
    pn_frame_options_default(&opt);
    opt.width = opt.height = 8;
    if (pn_init(&ctx, mem, bytes, &lim) != PN_OK || pn_scene_set(ctx, pos, 6, idx, 2) != PN_OK ||
        pn_render(ctx, &cam, &light, &opt, &out) != PN_OK) return 1;
    /* Compiled with the library's configuration (the package's or pkg-config's flags). */
    if ((pn_build_info() & 0xFFu) != PN_BUILD_ALGORITHMS) {
        printf("consumer: library algorithms 0x%x, this program's configuration 0x%x\n",
               (unsigned)(pn_build_info() & 0xFFu), (unsigned)PN_BUILD_ALGORITHMS);
        return 1;
    }
    printf("consumer: %ux%u frame, centre visibility %.3f, build info 0x%x\n", (unsigned)out.width,
           (unsigned)out.height, out.visibility[4 * 8 + 4], (unsigned)pn_build_info());
    free(mem);
    return 0;
}
