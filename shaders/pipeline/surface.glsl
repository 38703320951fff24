// A hit's colour (mapColor's, which sets gObject) and then its normal.
vec3 surfaceAt(vec3 p, out vec3 color) {
    mapColor(p, color);
    return calcNormal(p);
}
