// Modern view (issue 10): linear light. Each surface a ray meets gets the lights'
// diffuse and specular terms, the sky's ambient light (darkened by occlusion) and its
// emission; the rest goes to a mirror bounce weighted by Schlick's Fresnel from the
// material's mirror amount, fading with roughness. Every segment of the path is
// fogged. A miss shows the sky. Then exposure, an exponential tone map and sRGB.
vec3 radiance = vec3(0.0);
vec3 weight = vec3(1.0);
vec3 origin = ro;
vec3 dir = rd;
// @slot bounce-loop
    // @slot march
    if (t >= uDrawDist) {
        radiance += weight * sky(dir);
        break;
    }
    vec3 p = origin + dir * t;
    vec3 albedo;
    vec3 n = surfaceAt(p, albedo);
    albedo = pow(albedo, vec3(2.2));
    float mirror = gMirror;
    float roughness = gMaterial.x;
    // @slot primary-hit
    float cosView = clamp(dot(n, -dir), 0.0, 1.0);
    float f0 = mix(0.04, 1.0, mirror);
    float smoothness = 1.0 - roughness;
    float reflected = (f0 + (1.0 - f0) * pow(1.0 - cosView, 5.0)) * smoothness * smoothness;
    float occ = 1.0;
    // @slot occlusion
    vec3 direct = directLight(p, n, -dir, albedo, mirror, roughness@{light-args});
    vec3 skyLight = mix(uSkyHorizon, uSkyZenith, 0.5 + 0.5 * n.z);
    vec3 surface = (1.0 - reflected) * (direct + albedo * skyLight * (uAmbient * occ))
                   + albedo * gMaterial.y;
    // @slot surface
    float through = 1.0;
    // @slot segment
    weight *= through;
    radiance += weight * surface;
    weight *= reflected * mix(vec3(1.0), albedo, mirror);
    if (max(max(weight.r, weight.g), weight.b) < 0.002) {
        break;
    }
    origin = p + n * (2.0 * normalDelta(p));
    dir = dir - 2.0 * dot(dir, n) * n;
}
return pow(1.0 - exp(-radiance * uExposure), vec3(1.0 / 2.2));
