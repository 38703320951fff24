// Surface normal by one-sided differences, the article's: the gradient of map between
// p and p minus a small step along each axis. Four map evaluations, three of them in a
// loop from gZero (one copy of map for the three).
vec3 @{normal}(vec3 p) {
    float d = @{map}(p);
    float h = normalDelta(p);
    vec3 g = vec3(0.0);
    for (int axis = gZero; axis < 3; axis++) {
        vec3 e = axisStep(axis, h);
        g[axis] = d - @{map}(p - e);
    }
    return safeNormalize(g);
}
