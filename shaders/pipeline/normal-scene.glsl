// The normal of the whole scene's distance (normals-of :scene): the method's taps
// (normalTap) in one loop from gZero, so the compiler keeps one copy of map for all.
vec3 calcNormal(vec3 p) {
    float h = normalDelta(p);
    vec3 n = vec3(0.0);
    for (int j = gZero; j < kNormalTaps; j++) {
        vec3 w;
        vec3 e = normalTap(j, h, w);
        n += w * map(p + e);
    }
    return safeNormalize(n);
}
