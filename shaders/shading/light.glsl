// Lambert term toward the point light, clamped to [0, 1]. A light exactly at the
// point lights it along its normal (no NaN).
float lightness(vec3 p, vec3 n) {
    vec3 toLight = uLightPos - p;
    float lightDist = length(toLight);
    vec3 l = lightDist > 0.0 ? toLight / lightDist : n;
    float lambert = clamp(dot(l, n), 0.0, 1.0);
    // @slot shadow
    return lambert;
}
