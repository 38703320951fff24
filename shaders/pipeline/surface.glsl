// A hit's colour (mapColor's, which sets gObject) and then its normal; with `taps`,
// the surface taps (surface-taps.glsl) of the whole scene around it.
vec3 surfaceAt(vec3 p, out vec3 color, bool taps) {
    mapColor(p, color);
    vec3 n = calcNormal(p);
    for (int j = gZero; j < (taps ? kSurfaceTaps : 0); j++) {
        gEstimate = true;
        float d = map(surfaceTap(j, p, n));
        gEstimate = false;
        surfaceTaken(j, d);
    }
    return n;
}
