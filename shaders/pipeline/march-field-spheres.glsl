// The lean grid walk of march-field-alone.glsl for a field of spheres only: the same
// cells in the same order but the empty ones it jumps across, the same tests and
// results, in one loop whose every turn reads one texel of uFieldWalk
// (src/render/field.fnl's walk-texture; field.walk is this walk on the CPU). A turn
// either crosses a cell (its texel: the one sphere it lists, or where its list
// starts, or for an empty cell how far on the cells are empty, so it jumps there) or
// meets the next texel of the list of the cell it is in (a long list's first is the
// sphere about its spheres: missed, the cell is done). On llvmpipe every turn runs
// all of its code, branches included, and a loop nested in the walk runs its body at
// least once per turn (measured: even a loop of no turns cost a quarter of the
// frame): one texel and one sphere test per turn is the least a cell can cost.
uniform sampler2D uFieldWalk;  // cells, then their lists: a texel each
uniform int uFieldTurns;       // turns a walk can take, at most

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
    // Where the clearance of the ray's octant is in an empty cell's texel: which
    // float (pick) and which 8 bits of it (scale).
    int octant = (stride.x < 0.0 ? 1 : 0) + (stride.y < 0.0 ? 2 : 0) + (stride.z < 0.0 ? 4 : 0);
    vec3 pick = vec3(equal(ivec3(octant / 3), ivec3(0, 1, 2)));
    float scale = octant % 3 == 0 ? 1.0 : (octant % 3 == 1 ? 1.0 / 256.0 : 1.0 / 65536.0);
    int cells = int(uFieldDims.x * uFieldDims.y * uFieldDims.z);
    // The list being met: the texel of its next sphere, and how many are left. The
    // nearest entry into the cell's spheres so far.
    int next = 0;
    int left = 0;
    float hit = uDrawDist;
    for (int i = 0; i <= uFieldTurns; i++) {
        bool inList = left > 0;
        vec4 texel = fieldRead(uFieldWalk, uFieldRows.w, inList ? next : index);
        // A sphere: the next of the list, or the cell's one (radius > 0); or the
        // sphere about a long list's spheres, its first texel (radius < 0): when
        // the ray enters it past the cell (or not at all), none of them is the hit.
        bool bound = inList && texel.w < 0.0;
        float entry = fieldSphereEntry(q0, rd, vec4(texel.xyz, abs(texel.w)));
        bool sphere = (inList && !bound) || (!inList && texel.w > 0.0);
        hit = min(hit, sphere ? entry : uDrawDist);
        bool past = bound && entry > min(tNext.x, min(tNext.y, tNext.z));
        // A cell's list to meet: from the next turn on.
        bool starts = !inList && texel.w < 0.0;
        next = starts ? int(texel.x) : next + 1;
        left = starts ? int(texel.y) : (past ? 0 : max(left - 1, 0));
        steps += (!inList && texel.w != 0.0) ? 1 : 0;
        if (left == 0) {
            // The cell is done: an entry inside it is the hit; else on to the next,
            // or from an empty cell of clearance k (in the ray's octant) past the
            // empty cube of k cells on from it: where the ray leaves the cube
            // (cellEnd), the walls it has crossed along each axis by then (m), at
            // most k.
            float octantBits = floor(dot(texel.xyz, pick) * scale);
            float k = octantBits - 256.0 * floor(octantBits / 256.0);
            float far = (!inList && texel.w == 0.0) ? max(k - 1.0, 0.0) : 0.0;
            vec3 wall = tNext + far * tDelta;
            float cellEnd = min(wall.x, min(wall.y, wall.z));
            if (hit <= cellEnd && hit < tEnd) {
                return hit;
            }
            if (cellEnd >= tEnd) {
                return tPast;
            }
            if (steps >= uMaxSteps) {
                // (Where the walk stopped: the walls' crossings only grow.)
                t = max(t, cellEnd);
                break;
            }
            vec3 m = clamp(floor((cellEnd - tNext) / tDelta) + 1.0, 0.0, far + 1.0);
            tNext += m * tDelta;
            index += int(dot(m, stride));
            hit = uDrawDist;
            // (A ray that leaves the grid where its far wall rounds to just before
            // tEnd must not read the lists as cells.)
            if (index < 0 || index >= cells) {
                return tPast;
            }
        }
    }
    // @slot out-of-steps
    return t;
}

// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
