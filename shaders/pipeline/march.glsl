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
    // A shadow or mirror ray (not a primary one: those start at the camera, the
    // origin) whose first step is at its start must come nearer than startLimit of
    // the distance there (half of it; no limit in the article's fixed hit test) to
    // count a hit: one that starts within the hit threshold of a surface (in a
    // crease, or off a surface whose distance grows slower than 1) never hits at
    // its own start.
    float startHalf = 10000000000.0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = map(ro + rd * t);
        startHalf = i == 0 && t0 > 0.0 ? startLimit(d) : startHalf;
        float threshold = min(hitThreshold(t0 + t), startHalf);
        // @slot count-step
        t += d;
        if (d < threshold || t >= uDrawDist) {
            return t;
        }
    }
    // @slot out-of-steps
    return t;
}
