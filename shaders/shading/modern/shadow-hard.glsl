// Hard shadows (modern model): a light is hidden when the ray toward it meets
// something before it.
float visibility(vec3 o, vec3 l, float reach, float softness) {
    int shadowSteps;
    // @slot shadow-march
    return ts < reach ? 0.0 : 1.0;
}
