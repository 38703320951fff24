// Surface normal by the tetrahedron technique: four samples at the corners of a
// tetrahedron, k = (1,-1,-1), (-1,-1,1), (-1,1,-1), (1,1,1), give a central-difference
// quality gradient for four map evaluations, in a loop from gZero (one copy of map).
vec3 @{normal}(vec3 p) {
    float h = normalDelta(p);
    vec3 n = vec3(0.0);
    for (int i = gZero; i < 4; i++) {
        vec3 k = vec3(float(((i + 3) / 2) % 2), float((i / 2) % 2), float(i % 2)) * 2.0 - 1.0;
        n += k * @{map}(p + k * h);
    }
    return safeNormalize(n);
}
