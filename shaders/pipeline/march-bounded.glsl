// Sphere tracing with bounds (issue 11): the ground planes are met in closed form, and
// only the finite objects are marched (mapFinite), only from where the ray enters the
// first of their bounding spheres to where it leaves the last one, meets a plane or
// reaches tMax (a shadow ray ends at the light). Past the end it returns the plane's
// distance when the plane comes before tMax, else tMax itself: a miss.
// Otherwise the article's march: returns the distance travelled, steps counts distance
// evaluations, a hit is a distance below the draw distance (a ray out of steps counts
// where it stopped, as in the article).
float raymarchTo(vec3 ro, vec3 rd, float tMax, out int steps) {
    float t0 = length(ro);   // the camera is at the origin: distance already travelled
    float tPlane = planesHit(ro, rd);
    vec2 span = boundsSpan(ro, rd);
    float tEnd = min(min(tPlane, span.y), tMax);
    float t = max(span.x, 0.0);
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
        float threshold = min(hitThreshold(t0 + t), startHalf);
        // @slot count-step
        t += d;
        if (d < threshold) {
            return t;
        }
        if (t >= tEnd) {
            return min(tPlane, tMax);
        }
    }
    // @slot out-of-steps
    return t;
}

// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
