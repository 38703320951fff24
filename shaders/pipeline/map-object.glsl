// The distance to one object alone (`only`), or with `only` -1 to every object but
// one (`skip`; -1: none): the object a point lies on, which normals differentiate (a
// point where two objects meet gets the normal of the surface it lies on, not one
// pointing between them: with the whole scene's distance, a mirror bounce from such a
// crease lights a single pixel), and the others beside it (normal-crease.glsl). Each
// object is written once for every case, and normal-crease.glsl calls it in one loop
// (GLSL compilers inline every call, and each copy of the scene is its share of the
// compile); with one object d starts far above any distance, so its guard never skips
// it and d is its value.
float mapObject(vec3 p, int only, int skip) {
    bool all = only < 0;
    float d = all ? uDrawDist : 10000000000.0;
    // @slot object-terms
    return d;
}
