// Finite-difference step for normals, and the offset that starts shadow and mirror
// rays off a surface (twice this): the hit threshold at the point's distance from the
// camera, never below what float32 can resolve there.
float normalDelta(vec3 p) {
    float dist = length(p);
    return max(hitThreshold(dist), 0.000001 * (1.0 + dist));
}

// A unit vector along v, or straight up when v vanishes (no NaN).
vec3 safeNormalize(vec3 v) {
    float len = length(v);
    return len > 0.0 ? v / len : vec3(0.0, 0.0, 1.0);
}

// A step of h along axis 0, 1 or 2 (finite differences taken in a loop).
vec3 axisStep(int axis, float h) {
    return vec3(axis == 0 ? h : 0.0, axis == 1 ? h : 0.0, axis == 2 ? h : 0.0);
}

// @slot method
