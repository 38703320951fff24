// Shaded view: Lambert lighting, hard shadows and mirror bounces.
if (t >= uDrawDist) {
    vec3 background = uEnvColor;
    // @slot glow
    return background;
}
vec3 p = ro + rd * t;
vec3 surface;
vec3 n = surfaceAt(p, surface);
// @slot primary-hit
vec3 color = surface * lightness(p, n);
// @slot reflections
return color;
