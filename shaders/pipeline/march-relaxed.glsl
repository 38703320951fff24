// Over-relaxed sphere tracing (Keinert et al. 2014): steps of omega times the distance
// bound. When the bounding spheres of two consecutive points stop overlapping, the last
// step may have passed a surface: go back to the last safe point and continue with
// plain steps. Otherwise as the plain march: returns the distance travelled, steps
// counts distance evaluations, a hit is a distance below the draw distance.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    float t0 = length(ro);
    float t = 0.0;
    float tPrev = 0.0;
    float rPrev = 0.0;
    float omega = uRelaxation;
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
        // @slot count-step
        if (omega > 1.0 && abs(d) + rPrev < t - tPrev) {
            t = tPrev + rPrev;
            omega = 1.0;
            continue;
        }
        if (d < min(hitThreshold(t0 + t), startHalf)) {
            t += d;
            return t;
        }
        tPrev = t;
        rPrev = abs(d);
        t += omega * d;
        if (t >= uDrawDist) {
            return t;
        }
    }
    // @slot out-of-steps
    return t;
}
