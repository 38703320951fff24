// Fog: the fraction of light that crosses a segment of a ray (exponential in the
// density uFog.w, thinning with height by uFogFalloff: Quilez's closed form), and the
// fog's colour along a direction, tinted toward each sun's colour near it.
uniform vec4 uFog;                     // linear colour, density
uniform float uFogFalloff;             // per unit of height
uniform float uCamHeight;              // the camera's world z

float fogTransmittance(vec3 ro, vec3 rd, float t) {
    float k = uFogFalloff * rd.z * t;
    float thinning = abs(k) > 0.0001 ? (1.0 - exp(-k)) / k : 1.0;
    return exp(-uFog.w * exp(-uFogFalloff * (uCamHeight + ro.z)) * t * thinning);
}

vec3 fogColor(vec3 rd) {
    vec3 c = uFog.rgb;
    for (int i = 0; i < kLightCount; i++) {
        if (uLights[i].w == 0.0) {
            vec3 sun = uLightColors[i].rgb / max(max(uLightColors[i].r, uLightColors[i].g), max(uLightColors[i].b, 0.000001));
            c = mix(c, sun * max(max(uFog.r, uFog.g), uFog.b), pow(max(dot(rd, uLights[i].xyz), 0.0), 8.0));
        }
    }
    return c;
}
