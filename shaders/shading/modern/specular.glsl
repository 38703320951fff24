// Blinn-Phong specular, energy-normalised ((s + 8) / 8 against Lambert's 1), with
// Schlick's Fresnel from the reflectance at normal incidence: 0.04 for a plain
// surface up to 1 for a full mirror, tinted by the colour as the mirror amount grows.
// radiance: the light's, arriving (falloff, Lambert and shadow applied).
vec3 specularLight(vec3 n, vec3 l, vec3 v, vec3 albedo, float mirror, float roughness,
                   vec3 radiance) {
    vec3 h = safeNormalize(l + v);
    float shininess = exp2(1.0 + 10.0 * (1.0 - roughness));
    float f0 = mix(0.04, 1.0, mirror);
    float fresnel = f0 + (1.0 - f0) * pow(1.0 - clamp(dot(l, h), 0.0, 1.0), 5.0);
    return radiance * mix(vec3(1.0), albedo, mirror)
           * (fresnel * (shininess + 8.0) / 8.0 * pow(clamp(dot(n, h), 0.0, 1.0), shininess));
}
