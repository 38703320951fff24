// Surface normal by central differences: second-order accurate. Six map evaluations.
vec3 calcNormal(vec3 p) {
    vec2 e = vec2(normalDelta(p), 0.0);
    return safeNormalize(vec3(map(p + e.xyy) - map(p - e.xyy),
                              map(p + e.yxy) - map(p - e.yxy),
                              map(p + e.yyx) - map(p - e.yyx)));
}
