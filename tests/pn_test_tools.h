/* pn_test_tools.h - for the tools-linked variants of the core tests (PN_TEST_MODELS=1,
 * tests/CMakeLists.txt): a scene the tools load (a shared .glb through pn_setup_load, with
 * the automatic view and light) as a pn_test_scene, so the checks the core tests run on
 * their own scenes run on the real models too. Include after pn_test_scene.h; links
 * pn_tools. */
#ifndef PN_TEST_TOOLS_H
#define PN_TEST_TOOLS_H

#include "pn_setup.h"
#include "pn_test_scene.h"

/* pn_setup_load(source, builtin, ground) into *t, which takes the mesh's arrays over (free
 * with pn_test_scene_free). The bounding box, diagonal and eps are the setup's: those of
 * the scene without the ground the loader appends. 0 on success, else a message on stderr. */
static inline int pn_test_scene_load_tools(pn_test_scene *t, const char *source, int builtin, int ground)
{
    pn_setup s;
    char err[256];
    memset(t, 0, sizeof(*t));
    if (pn_setup_load(&s, source, builtin, ground, err, sizeof(err)) != 0) {
        fprintf(stderr, "%s: %s\n", source, err);
        return 1;
    }
    t->mesh = s.mesh; /* the same pn_mesh */
    t->camera = s.camera;
    t->light = s.light;
    t->diag = s.diag;
    t->eps = s.eps;
    snprintf(t->name, sizeof(t->name), "%s", s.name);
    return 0;
}

#endif
