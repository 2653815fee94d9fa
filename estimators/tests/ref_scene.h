/* ref_scene.h - the reference scenes (ref_irradiance.h, generated) as
 * mcest_scene values, looked up by name; shared by the irradiance tests. */
#ifndef MCEST_TEST_REF_SCENE_H
#define MCEST_TEST_REF_SCENE_H

#include "mcest.h"
#include "ref_irradiance.h"

#include <string.h>

static const ref_scene *find(const char *name)
{
    for (int i = 0; i < N_REF_SCENES; i++)
        if (!strcmp(ref_scenes[i].name, name))
            return &ref_scenes[i];
    return NULL;
}

static mcest_scene scene_of(const ref_scene *r)
{
    mcest_scene s;
    memcpy(s.triangle, r->tri, sizeof s.triangle);
    memcpy(s.point, r->point, sizeof s.point);
    memcpy(s.normal, r->normal, sizeof s.normal);
    s.radiance = r->radiance;
    return s;
}

#endif
