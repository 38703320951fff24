// Surface normal by one-sided differences, the article's: the gradient of map between
// p and p minus a small step along each axis. Four map evaluations.
vec3 calcNormal(vec3 p) {
    float d = map(p);
    vec2 e = vec2(normalDelta(p), 0.0);
    return safeNormalize(vec3(d - map(p - e.xyy), d - map(p - e.yxy), d - map(p - e.yyx)));
}
