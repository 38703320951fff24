// The sky (modern model): a gradient from the horizon colour up to the zenith colour,
// darkening below the horizon, and a disc for each sun (uSunEdge: the cosines of the
// disc's outer and inner radius). Colours are linear.
vec3 sky(vec3 rd) {
    vec3 c = mix(uSkyHorizon, uSkyZenith, sqrt(clamp(rd.z, 0.0, 1.0)));
    c *= 1.0 - 0.5 * clamp(-4.0 * rd.z, 0.0, 1.0);
    for (int i = 0; i < kLightCount; i++) {
        if (uLights[i].w == 0.0) {
            c += uLightColors[i].rgb * (8.0 * smoothstep(uSunEdge.x, uSunEdge.y, dot(rd, uLights[i].xyz)));
        }
    }
    return c;
}
