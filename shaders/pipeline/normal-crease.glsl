// A hit's colour and normal. The normal where the nearest object meets another:
// where some other object comes within the finite differences' reach, the nearest
// object's normal is taken at the point pushed out of that reach, away from the
// others. An object standing on the floor, or on another, then gets its side face's
// normal, not a blend with its own bottom edge, which lies in the crease.
//
// One loop from gZero, one call of mapObject: the scene's one copy for every query
// (GLSL compilers inline every call). Turn -1 is mapColor's query (the colour, and
// the nearest object in gObject: one with an exact normal has it then, and goes on to
// the surface taps). Turn 0 finds how near the others come (every object but
// gObject); only when that is within reach, turns 1-6 take their central
// differences, and the point is pushed out. Turns 7 to 6 + kNormalTaps are the
// method's taps (normalTap) of the nearest object's own distance at that point; with
// `taps`, the turns after them are the surface taps (surface-taps.glsl) of the whole
// scene around the hit.
vec3 exactNormal(vec3 p) {
    // The nearest object's exact normal (gObject's); none: vec3(0.0).
    // @slot exact
    return vec3(0.0);
}

vec3 surfaceAt(vec3 p, out vec3 color, bool taps) {
    color = vec3(0.0);
    vec3 hit = p;
    float h = normalDelta(p);
    int object = -1;  // -1: no object found, every one
    float other = 0.0;
    vec3 g = vec3(0.0);
    vec3 n = vec3(0.0);
    vec3 normal = vec3(0.0);
    int first = 7 + kNormalTaps;  // the first surface tap
    for (int i = gZero - 1; i < first + (taps ? kSurfaceTaps : 0); i++) {
        bool crease = i < 7;
        bool around = i >= first;
        int axis = i > 0 ? (i - 1) / 2 : 3;
        float s = i > 0 && i == 2 * axis + 1 ? 1.0 : -1.0;
        vec3 w;
        if (i == first && normal == vec3(0.0)) {
            normal = safeNormalize(n);
        }
        vec3 q = i < 0 ? p : around ? surfaceTap(i - first, hit, normal)
                 : p + (crease ? s * axisStep(axis, h) : normalTap(i - 7, h, w));
        gEstimate = around;
        float d = mapObject(q, crease || around ? -1 : object, i < 0 || around ? -1 : crease ? gObject : -1, i < 0, color);
        if (i < 0) {
            object = gObject;
            normal = exactNormal(p);
            if (normal != vec3(0.0)) i = first - 1;  // exact: on to the surface taps
        } else if (around) {
            surfaceTaken(i - first, d);
        } else if (i == 0) {
            other = d;
            if (other >= 2.0 * h) i = 6;  // no other within reach: on to the taps
        } else if (crease) {
            g[axis] += s * d;
        } else {
            n += w * d;
        }
        if (i == 6) {
            if (other < 2.0 * h) {
                p += safeNormalize(g) * (2.0 * h - other);
            }
            h = normalDelta(p);
        }
    }
    gEstimate = false;
    return normal == vec3(0.0) ? safeNormalize(n) : normal;
}
