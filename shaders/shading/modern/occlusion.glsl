// Ambient occlusion: five samples along the normal out to uAo.y; each finds how much
// nearer the surfaces are than its own height, the nearer samples weighing more.
// uAo.x scales the darkening. The samples are taken by occlusion() below, or, when the
// scene has soft shadows, as the first turns of the first light's soft shadow march
// (occlusion-taps.glsl: one copy of the scene's distance for both; GLSL compilers
// inline every call, and each copy is its share of the compile).
uniform vec2 uAo;                      // strength, radius

const int kOcclusionTaps = 5;

// The height along the normal of sample k (1 to kOcclusionTaps).
float occlusionHeight(int k) {
    return uAo.y * float(k) / 5.0;
}

// The samples' sums s (weighted nearness, the next sample's weight, the weights'
// total, from vec3(0.0, 1.0, 0.0)) with a sample at height h that found distance d.
vec3 occlusionTake(vec3 s, float h, float d) {
    return vec3(s.x + s.y * clamp((h - d) / h, 0.0, 1.0), s.y * 0.5, s.z + s.y);
}

// The sky light's share left by the samples' sums s.
float occlusionOf(vec3 s) {
    return clamp(1.0 - uAo.x * s.x / s.z, 0.0, 1.0);
}

float occlusion(vec3 p, vec3 n) {
    vec3 s = vec3(0.0, 1.0, 0.0);
    // The distances are estimates here, not steps (see gEstimate).
    gEstimate = true;
    for (int k = 1; k <= kOcclusionTaps; k++) {
        float h = occlusionHeight(k);
        s = occlusionTake(s, h, map(p + n * h));
    }
    gEstimate = false;
    return occlusionOf(s);
}
