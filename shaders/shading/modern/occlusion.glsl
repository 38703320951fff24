// Ambient occlusion: five samples along the normal out to uAo.y; each finds how much
// nearer the surfaces are than its own height, the nearer samples weighing more.
// uAo.x scales the darkening.
uniform vec2 uAo;                      // strength, radius

float occlusion(vec3 p, vec3 n) {
    float occ = 0.0;
    float weight = 1.0;
    float total = 0.0;
    // The distances are estimates here, not steps (see gEstimate).
    gEstimate = true;
    for (int i = 1; i <= 5; i++) {
        float h = uAo.y * float(i) / 5.0;
        float d = map(p + n * h);
        occ += weight * clamp((h - d) / h, 0.0, 1.0);
        total += weight;
        weight *= 0.5;
    }
    gEstimate = false;
    return clamp(1.0 - uAo.x * occ / total, 0.0, 1.0);
}
