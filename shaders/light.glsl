// Lambert term toward the point light, clamped to [0, 1].
float lightness(vec3 p, vec3 n) {
    vec3 l = normalize(uLightPos - p);
    float lambert = clamp(dot(l, n), 0.0, 1.0);
    // @slot shadow
    return lambert;
}
