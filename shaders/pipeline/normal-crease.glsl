// The normal where the nearest object meets another: where some other object comes
// within the finite differences' reach, the nearest object's normal is taken at the
// point pushed out of that reach, away from the others. An object standing on the
// floor, or on another, then gets its side face's normal, not a blend with its own
// bottom edge, which lies in the crease.
vec3 calcNormal(vec3 p) {
    // @slot exact
    float h = normalDelta(p);
    float other = mapOthers(p);
    if (other < 2.0 * h) {
        // Central differences of the others, in a loop from gZero (one copy of them).
        vec3 g = vec3(0.0);
        for (int i = gZero; i < 6; i++) {
            int axis = i / 2;
            float s = i == 2 * axis ? 1.0 : -1.0;
            vec3 e = vec3(axis == 0 ? h : 0.0, axis == 1 ? h : 0.0, axis == 2 ? h : 0.0);
            g[axis] += s * mapOthers(p + s * e);
        }
        vec3 away = safeNormalize(g);
        p += away * (2.0 * h - other);
    }
    return objectNormal(p);
}
