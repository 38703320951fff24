// A hit's colour and normal. The normal where the nearest object meets another:
// where some other object comes within the finite differences' reach, the nearest
// object's normal is taken at the point pushed out of that reach, away from the
// others. An object standing on the floor, or on another, then gets its side face's
// normal, not a blend with its own bottom edge, which lies in the crease.
//
// One loop from gZero, one call of mapObject: the scene's one copy for every query
// (GLSL compilers inline every call). Turn -1 is mapColor's query (the colour, and
// the nearest object in gObject: one with an exact normal returns it then). Turn 0
// finds how near the others come (every object but gObject); only when that is within
// reach, turns 1-6 take their central differences, and the point is pushed out.
// Turns 7 on are the method's taps (normalTap) of the nearest object's own distance
// at that point.
vec3 surfaceAt(vec3 p, out vec3 color) {
    color = vec3(0.0);
    float h = normalDelta(p);
    int object = -1;  // -1: no object found, every one
    float other = 0.0;
    vec3 g = vec3(0.0);
    vec3 n = vec3(0.0);
    for (int i = gZero - 1; i < 7 + kNormalTaps; i++) {
        bool crease = i < 7;
        int axis = i > 0 ? (i - 1) / 2 : 3;
        float s = i > 0 && i == 2 * axis + 1 ? 1.0 : -1.0;
        vec3 w;
        vec3 e = i < 0 ? vec3(0.0) : crease ? s * axisStep(axis, h) : normalTap(max(i - 7, 0), h, w);
        float d = mapObject(p + e, crease ? -1 : object, i < 0 ? -1 : crease ? gObject : -1, i < 0, color);
        if (i < 0) {
            object = gObject;
            // @slot exact
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
    return safeNormalize(n);
}
