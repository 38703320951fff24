// Rim light: the sky's light along the normal, times the albedo, growing as the view
// grazes the surface (cosView from 1 facing the viewer to 0 edge-on). uRim.x is the
// strength, uRim.y the power: higher, a thinner rim.
uniform vec2 uRim;

vec3 rimLight(float cosView, vec3 albedo, vec3 skyLight) {
    return albedo * skyLight * (uRim.x * pow(1.0 - cosView, uRim.y));
}
