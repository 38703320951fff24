// The distance to one object alone: the one the last mapColor call found nearest
// (gObject). Normals differentiate it, so a point where two objects meet gets the
// normal of the surface it lies on, not one pointing between them (with the whole
// scene's distance, a mirror bounce from such a crease lights a single pixel).
// With no object found (gObject -1) every object is taken: the whole scene's distance,
// as map's. A tree object is written once for both cases (GLSL compilers inline every
// call, and each copy of the scene is its share of the compile); with one object d
// starts far above any distance, so its guard never skips it and d is its value.
float mapObject(vec3 p) {
    bool all = gObject < gZero;  // gZero: 0 (prelude.glsl)
    bool take;  // whether the next object is taken: every one, or gObject's
    float d = all ? uDrawDist : 10000000000.0;
    // @slot object-terms
    return d;
}

// The distance to every object but that one: what a point on it has beside it.
float mapOthers(vec3 p) {
    float d = uDrawDist;
    // @slot others-terms
    return d;
}
