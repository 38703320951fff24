// The surface taps: distance queries around a hit that lighting features read
// (ambient occlusion's samples along the normal; a feature's :taps in
// src/render/features.fnl). surfaceAt takes them in its own loop after the normal, so
// the scene's code is there once for them too (GLSL compilers inline every call):
// surfaceTap gives tap j's point from the hit and its normal, surfaceTaken the whole
// scene's distance there, read as an estimate (see gEstimate), taps in order.
const int kSurfaceTaps = @{count};
// @slot features

vec3 surfaceTap(int j, vec3 p, vec3 n) {
    // @slot points
    return p;
}

void surfaceTaken(int j, float d) {
    // @slot taken
}
