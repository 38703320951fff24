// Surface normal by the tetrahedron technique: four samples at the corners of a
// tetrahedron give a central-difference quality gradient for four map evaluations.
vec3 calcNormal(vec3 p) {
    float h = normalDelta(p);
    vec2 k = vec2(1.0, -1.0);
    return safeNormalize(k.xyy * map(p + k.xyy * h) + k.yyx * map(p + k.yyx * h) +
                         k.yxy * map(p + k.yxy * h) + k.xxx * map(p + k.xxx * h));
}
