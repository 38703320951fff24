// Sphere tracing as in the article: step along the ray by the distance bound until a
// step falls under the hit threshold, the ray passes the draw distance, or the step
// budget is spent. Returns the distance travelled; steps counts distance evaluations
// (only in shaders whose view reads it).
// A ray counts as a hit when the returned distance is below the draw distance.
// (One combined exit test: llvmpipe runs it faster than two separate branches.)
float raymarch(vec3 ro, vec3 rd, out int steps) {
    float t0 = length(ro);   // the camera is at the origin: distance already travelled
    float t = 0.0;
    steps = 0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = map(ro + rd * t);
        float threshold = hitThreshold(t0 + t);
        // @slot count-step
        t += d;
        if (d < threshold || t >= uDrawDist) {
            return t;
        }
    }
    // @slot out-of-steps
    return t;
}
