// Over-relaxed sphere tracing (Keinert et al. 2014) with bounds: as march-bounded.glsl
// (planes in closed form, the finite objects marched over the span of their bounding
// spheres), with steps of omega times the distance bound and the fall back to the last
// safe point of march-relaxed.glsl.
float raymarchTo(vec3 ro, vec3 rd, float tMax, out int steps) {
    float t0 = length(ro);
    float tPlane = planesHit(ro, rd);
    vec2 span = boundsSpan(ro, rd);
    float tEnd = min(min(tPlane, span.y), tMax);
    float t = max(span.x, 0.0);
    float tPrev = t;
    float rPrev = 0.0;
    float omega = uRelaxation;
    steps = 0;
    if (t >= tEnd) {
        return min(tPlane, tMax);
    }
    // A shadow or mirror ray (not a primary one: those start at the camera, the
    // origin) whose first step is at its start must come nearer than startLimit of
    // the distance there (half of it; no limit in the article's fixed hit test) to
    // count a hit: one that starts within the hit threshold of a surface (in a
    // crease, or off a surface whose distance grows slower than 1) never hits at
    // its own start.
    float startHalf = 10000000000.0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = mapFinite(ro + rd * t);
        startHalf = i == 0 && t == 0.0 && t0 > 0.0 ? startLimit(d) : startHalf;
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
        if (t >= tEnd) {
            // An over-relaxed step past the end may have jumped a surface: only a
            // plain step past it ends the march; otherwise go on from the plain step.
            if (tPrev + rPrev >= tEnd) {
                return min(tPlane, tMax);
            }
            t = tPrev + rPrev;
            omega = 1.0;
        }
    }
    // @slot out-of-steps
    return t;
}

// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
