// The grid walk of march-field.glsl when the field is the only finite thing in the
// scene (beside ground planes): nothing is sphere-traced, so the walk is lean, one
// cell per turn of the loop. The same cells, tests and results as march-field.glsl.
float raymarchTo(vec3 ro, vec3 rd, float tMax, out int steps) {
    float tPlane = planesHit(ro, rd);
    float tPast = min(tPlane, tMax);
    vec3 q0, inv, tNext, tDelta, stride;
    float gridIn, tEnd;
    int index;
    steps = 0;
    if (!fieldWalkStart(ro, rd, tPast, q0, inv, gridIn, tEnd, index, tNext, tDelta, stride)) {
        return tPast;
    }
    float t = gridIn;
    for (int i = 0; i <= uFieldCrossings; i++) {
        float cellEnd = min(tNext.x, min(tNext.y, tNext.z));
        vec4 list = fieldRead(uFieldCells, uFieldRows.x, index);
        // (No branch around an empty cell's test: its loop has nothing to do.)
        steps += list.y > 0.0 ? 1 : 0;
        float hit = fieldListEntry(int(list.x), int(list.y), q0, rd, inv);
        if (hit <= cellEnd && hit < tEnd) {
            return hit;
        }
        t = max(t, cellEnd);
        if (t >= tEnd) {
            return tPast;
        }
        if (steps >= uMaxSteps) {
            break;
        }
        fieldNextCell(tNext, index, tDelta, stride);
    }
    // @slot out-of-steps
    return t;
}

// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
