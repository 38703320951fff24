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
        vec2 e = vec2(h, 0.0);
        vec3 away = safeNormalize(vec3(mapOthers(p + e.xyy) - mapOthers(p - e.xyy),
                                       mapOthers(p + e.yxy) - mapOthers(p - e.yxy),
                                       mapOthers(p + e.yyx) - mapOthers(p - e.yyx)));
        p += away * (2.0 * h - other);
    }
    return objectNormal(p);
}
