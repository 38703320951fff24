// Direct light (modern model): each light's Lambert term and, when the scene has it,
// Blinn-Phong specular weighted by Schlick's Fresnel, times the light's visibility
// (its shadow) and a point light's falloff. uLights[i]: a point light's position
// and its range (w > 0), or the direction toward a sun (w = 0); uLightColors[i]: linear
// colour times intensity, and the light's softness. Linear colours. When the soft
// shadow takes ambient occlusion's samples (occlusion-taps.glsl), the first light's
// march runs lit or not, and occ (the view's) takes their share.
vec3 directLight(vec3 p, vec3 n, vec3 v, vec3 albedo, float mirror, float roughness@{params}) {
    vec3 c = vec3(0.0);
    vec3 origin = p + n * (2.0 * normalDelta(p));
    for (int i = 0; i < kLightCount; i++) {
        vec4 light = uLights[i];
        vec3 l = light.xyz;
        float reach = uDrawDist;
        float falloff = 1.0;
        if (light.w > 0.0) {
            vec3 toLight = light.xyz - p;
            float dist = length(toLight);
            l = dist > 0.0 ? toLight / dist : n;
            float r = dist / light.w;
            falloff = 1.0 / (1.0 + r * r);
            // As the classic shadow ray: it ends short of the light by the normal offset.
            reach = min(dist - 2.0 * normalDelta(light.xyz), uDrawDist);
        }
        float lambert = dot(n, l);
        float visible = 1.0;
        // @slot shadow-taps
        if (lambert > 0.0) {
            // @slot shadow
            vec3 radiance = uLightColors[i].rgb * (falloff * lambert * visible);
            c += albedo * radiance;
            // @slot light
        }
    }
    return c;
}
