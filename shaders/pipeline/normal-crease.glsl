// The normal where the nearest object meets another: where some other object comes
// within the finite differences' reach, the nearest object's normal is taken at the
// point pushed out of that reach, away from the others. An object standing on the
// floor, or on another, then gets its side face's normal, not a blend with its own
// bottom edge, which lies in the crease.
vec3 calcNormal(vec3 p) {
    // @slot exact
    float h = normalDelta(p);
    // Turn 0 finds how near the others come; only when that is within reach, turns
    // 1-6 take their central differences. One loop from gZero: one copy of mapOthers.
    float other = 0.0;
    vec3 g = vec3(0.0);
    for (int i = gZero; i < 7; i++) {
        int axis = i > 0 ? (i - 1) / 2 : 3;
        float s = i > 0 && i == 2 * axis + 1 ? 1.0 : -1.0;
        vec3 e = axisStep(axis, h);
        float d = mapOthers(p + s * e);
        if (i == 0) {
            other = d;
            if (other >= 2.0 * h) break;
        } else {
            g[axis] += s * d;
        }
    }
    if (other < 2.0 * h) {
        p += safeNormalize(g) * (2.0 * h - other);
    }
    return objectNormal(p);
}
