// Through a field's grid (issue 12), with bounds as in march-bounded.glsl: the ground
// planes met in closed form, the other finite objects (mapFinite) sphere-traced over
// the span of their bounding spheres. The ray walks the grid's cells in order (a 3D
// DDA); in each it meets the objects the cell lists in closed form (fieldListEntry):
// an entry inside the cell, and before any other object can be, is the hit. A step
// never passes the cell's far wall, where the next cell's list takes over. An empty
// cell, with nothing else near, costs one texel; steps counts the cells and points
// where something was evaluated, and only those spend uMaxSteps.
float raymarchTo(vec3 ro, vec3 rd, float tMax, out int steps) {
    float t0 = length(ro);   // the camera is at the origin: distance already travelled
    float tPlane = planesHit(ro, rd);
    vec2 span = boundsSpan(ro, rd);
    vec3 q0 = ro - uFieldOrigin;
    vec3 safe = fieldSafeDirection(rd);
    vec3 inv = 1.0 / safe;
    vec2 box = fieldBoxSpan(q0, inv);
    float gridIn = box.x;
    float gridOut = box.y;
    bool grid = gridIn < gridOut;
    float tEnd = min(min(tPlane, max(span.y, grid ? gridOut : 0.0)), tMax);
    float t = max(min(span.x, grid ? gridIn : uDrawDist), 0.0);
    steps = 0;
    if (t >= tEnd) {
        return min(tPlane, tMax);
    }
    // The walk: 0 before the grid, 1 in a cell, 2 past the grid. cellEnd is where the
    // field's part changes next (the grid's entry, the cell's far wall).
    int state = grid ? 0 : 2;
    float cellEnd = grid ? gridIn : uDrawDist;
    ivec3 cell = ivec3(0);
    ivec3 dims = ivec3(uFieldDims);
    ivec3 stepDir = ivec3(sign(safe));
    vec3 tDelta = uFieldCell * abs(inv);
    vec3 tNext = vec3(0.0);
    int evals = 0;
    // A shadow or mirror ray (not a primary one: those start at the camera, the
    // origin) whose first step is at its start must come nearer than startLimit of
    // the distance there (half of it; no limit in the article's fixed hit test) to
    // count a hit: one that starts within the hit threshold of a surface (in a
    // crease, or off a surface whose distance grows slower than 1) never hits at
    // its own start.
    float startHalf = 10000000000.0;
    for (int i = 0; i < uMaxSteps + uFieldCrossings + 1; i++) {
        if (state == 0 && t >= gridIn) {
            vec3 q = q0 + rd * t;
            cell = clamp(ivec3(floor(q / uFieldCell)), ivec3(0), dims - 1);
            vec3 wall = (vec3(cell) + step(vec3(0.0), safe)) * uFieldCell;
            tNext = (wall - q0) * inv;
            state = 1;
            cellEnd = min(tNext.x, min(tNext.y, tNext.z));
        }
        vec3 p = ro + rd * t;
        float d = @{map}(p@{ray});
        startHalf = i == 0 && t == 0.0 && t0 > 0.0 ? startLimit(d) : startHalf;
        bool evaluated = kFieldOthers;
        if (state == 1) {
            vec4 list = fieldRead(uFieldCells, uFieldRows.x, fieldCellIndex(cell));
            if (list.y > 0.0) {
                float hit = fieldListEntry(int(list.x), int(list.y), q0, rd, inv);
                evaluated = true;
                if (hit <= min(t + d, cellEnd) && hit < tEnd) {
                    steps = evals + 1;
                    return hit;
                }
            }
        }
        if (evaluated) {
            evals++;
            steps = evals;
            if (d < min(hitThreshold(t0 + t), startHalf)) {
                return t + d;
            }
        }
        if (t + d < cellEnd) {
            t += d;
        } else {
            // The step reaches the far wall: on to the next cell along the ray.
            t = max(t, cellEnd);
            if (state == 0) {
                // (the grid's entry: the cell is found at the top of the loop)
            } else if (state == 1) {
                // On along the axis (or axes, at a tie) whose wall comes first.
                vec3 m = step(tNext, min(tNext.yzx, tNext.zxy));
                tNext += m * tDelta;
                cell += ivec3(m) * stepDir;
                if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, dims))) {
                    state = 2;
                    cellEnd = uDrawDist;
                } else {
                    cellEnd = min(tNext.x, min(tNext.y, tNext.z));
                }
            }
        }
        if (t >= tEnd) {
            return min(tPlane, tMax);
        }
        if (evals >= uMaxSteps) {
            break;
        }
    }
    // @slot out-of-steps
    return t;
}

// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
