// Ambient occlusion: five samples along the normal out to uAo.y; each finds how much
// nearer the surfaces are than its own height, the nearer samples weighing more.
// uAo.x scales the darkening. The samples are surface taps (surface-taps.glsl):
// surfaceAt takes them in its own loop, in order, and leaves the factor in gOcclusion.
uniform vec2 uAo;                      // strength, radius

float gOcclusion = 1.0;        // the factor of the last hit's samples
float gOcclusionSum = 0.0;     // the weighted samples so far
float gOcclusionTotal = 0.0;   // their weights
float gOcclusionWeight = 1.0;  // the next one's

vec3 occlusionTap(int j, vec3 p, vec3 n) {
    return p + n * (uAo.y * float(j + 1) / 5.0);
}

void occlusionTaken(int j, float d) {
    if (j == 0) {
        gOcclusionSum = 0.0;
        gOcclusionTotal = 0.0;
        gOcclusionWeight = 1.0;
    }
    float h = uAo.y * float(j + 1) / 5.0;
    gOcclusionSum += gOcclusionWeight * clamp((h - d) / h, 0.0, 1.0);
    gOcclusionTotal += gOcclusionWeight;
    gOcclusionWeight *= 0.5;
    gOcclusion = clamp(1.0 - uAo.x * gOcclusionSum / gOcclusionTotal, 0.0, 1.0);
}
