// Surface normal by central differences: second-order accurate. Six map evaluations,
// in a loop from gZero so that the compiler keeps one copy of map, not six.
vec3 @{normal}(vec3 p) {
    float h = normalDelta(p);
    vec3 g = vec3(0.0);
    for (int i = gZero; i < 6; i++) {
        int axis = i / 2;
        float s = i == 2 * axis ? 1.0 : -1.0;
        vec3 e = axisStep(axis, h);
        g[axis] += s * @{map}(p + s * e);
    }
    return safeNormalize(g);
}
