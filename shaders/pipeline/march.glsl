// @part march
// Sphere tracing, one march in four forms that the plan picks (src/render/codegen.fnl,
// march-lines): plain or over-relaxed, unbounded or bounded.
// - Plain (the article's): step along the ray by the distance bound until a step falls
//   under the hit threshold, the ray passes the draw distance, or the step budget is
//   spent. (One combined exit test: llvmpipe runs it faster than two branches.)
// - Over-relaxed (Keinert et al. 2014): steps of omega times the distance bound. When
//   the bounding spheres of two consecutive points stop overlapping, the last step may
//   have passed a surface: go back to the last safe point and continue with plain steps.
// - Bounded (issue 11): the ground planes are met in closed form, and only the finite
//   objects are marched (mapFinite), only from where the ray enters the first of their
//   bounding spheres to where it leaves the last one, meets a plane or reaches tMax (a
//   shadow ray ends at the light). Past the end it returns the plane's distance when
//   the plane comes before tMax, else tMax itself: a miss.
// Each returns the distance travelled; steps counts distance evaluations (only in
// shaders whose view reads it); a hit is a distance below the draw distance (a ray out
// of steps counts where it stopped, as in the article).
float @{march}(vec3 ro, vec3 rd, @{range}out int steps) {
    float t0 = length(ro);   // the camera is at the origin: distance already travelled
    // @slot start
    steps = 0;
    // @slot before-loop
    // A shadow or mirror ray (not a primary one: those start at the camera, the
    // origin) whose first step is at its start must come nearer than startLimit of
    // the distance there (half of it; no limit in the article's fixed hit test) to
    // count a hit: one that starts within the hit threshold of a surface (in a
    // crease, or off a surface whose distance grows slower than 1) never hits at
    // its own start.
    float startHalf = 10000000000.0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = @{map}(ro + rd * t@{ray});
        startHalf = i == 0 && @{first}t0 > 0.0 ? startLimit(d) : startHalf;
        // @slot step
    }
    // @slot out-of-steps
    return t;
}

// @part start-unbounded
float t = 0.0;

// @part start-bounded
float tPlane = planesHit(ro, rd);
vec2 span = boundsSpan(ro, rd);
float tEnd = min(min(tPlane, span.y), tMax);
float t = max(span.x, 0.0);

// @part relaxed-state
float tPrev = @{t-prev};
float rPrev = 0.0;
float omega = uRelaxation;

// @part before-bounded
if (t >= tEnd) {
    return min(tPlane, tMax);
}

// @part step-plain
float threshold = min(hitThreshold(t0 + t), startHalf);
// @slot count-step
t += d;
if (d < threshold || t >= uDrawDist) {
    return t;
}

// @part step-plain-bounded
float threshold = min(hitThreshold(t0 + t), startHalf);
// @slot count-step
t += d;
if (d < threshold) {
    return t;
}
if (t >= tEnd) {
    return min(tPlane, tMax);
}

// @part step-relaxed
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
// @slot relaxed-end

// @part relaxed-end-unbounded
if (t >= uDrawDist) {
    return t;
}

// @part relaxed-end-bounded
if (t >= tEnd) {
    // An over-relaxed step past the end may have jumped a surface: only a
    // plain step past it ends the march; otherwise go on from the plain step.
    if (tPrev + rPrev >= tEnd) {
        return min(tPlane, tMax);
    }
    t = tPrev + rPrev;
    omega = 1.0;
}

// @part to-draw-distance
// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
