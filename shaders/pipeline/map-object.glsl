// The scene's every query of a hit, its objects written once for all (GLSL compilers
// inline every call, and each copy of the scene is its share of the compile):
// - with `materials`, mapColor's: the nearest object's distance and colour, its
//   number in gObject (its materials computed only where it is the nearest so far);
// - else the distance to one object alone (`only`), the one a point lies on, which
//   normals differentiate (a point where two objects meet gets the normal of the
//   surface it lies on, not one pointing between them: with the whole scene's
//   distance, a mirror bounce from such a crease lights a single pixel); with one
//   object d starts far above any distance, so its guard never skips it;
// - or with `only` -1, every object but one (`skip`; -1: none): the others beside
//   that point (normal-crease.glsl).
// normal-crease.glsl's surfaceAt calls it once, in one loop, for a hit's colour and
// normal.
float mapObject(vec3 p, int only, int skip, bool materials, inout vec3 color) {
    bool all = only < 0;
    float d = all ? uDrawDist : 10000000000.0;
    if (materials) {
        color = vec3(0.0);
        // @slot color-start
    }
    // @slot object-terms
    return d;
}
