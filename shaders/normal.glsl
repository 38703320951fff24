// Surface normal by one-sided differences, as in the article: the gradient of map
// between p and p minus epsilon along each axis.
vec3 calcNormal(vec3 p) {
    float d = map(p);
    vec2 e = vec2(uEpsilon, 0.0);
    return normalize(vec3(d - map(p - e.xyy), d - map(p - e.yxy), d - map(p - e.yyx)));
}
