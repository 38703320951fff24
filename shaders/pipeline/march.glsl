// The primary march: every shader's one raymarchTo (raymarch when unbounded), made
// from this chunk alone by src/render/codegen.fnl (march-lines). Part `march` is the
// skeleton every form shares: the form's comment (slot about), the signature, the
// start (slot start), steps = 0, what comes before the loop (an early exit, the
// walk's state), a loop of @{turns} turns whose body is slot step, and what a ray out
// of turns returns (slot out-of-steps); bounded, raymarch is raymarchTo up to the
// draw distance (to-draw-distance). The other parts fill its slots, one form each:
// - Sphere tracing (about-trace): plain or over-relaxed, unbounded or bounded. Its
//   distance at each step and its start's hit limit (trace-start, trace-before,
//   trace-step) are shared with the field's general walk.
// - Through a field's grid (about-field): the general walk, where other finite
//   objects are sphere-traced alongside the grid's cells; its start is the bounded
//   march's with the grid's span joined to the bounding spheres' (grid-span), and it
//   enters and crosses cells as the lean walks do (fieldCellAt, fieldNextWall).
// - The field's lean walks, where the field is the only finite thing (beside ground
//   planes), from one start (start-walk, before-walk; fieldWalkStart and
//   fieldNextCell are in field.glsl): one cell a turn (about-cells, step-cells), or
//   for a field of spheres only one texel a turn (about-spheres, spheres-state,
//   step-spheres).
// Every form returns the distance travelled; a hit is a distance below the draw
// distance (a ray out of steps counts where it stopped, as in the article, unless
// the out-of-steps slot says otherwise).

// @part march
// @slot about
float @{march}(vec3 ro, vec3 rd, @{range}out int steps) {
    // @slot start
    steps = 0;
    // @slot before-loop
    for (int i = 0; i < @{turns}; i++) {
        // @slot step
    }
    // @slot out-of-steps
    return t;
}

// @part about-trace
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

// @part trace-start
float t0 = length(ro);   // the camera is at the origin: distance already travelled

// @part trace-before
// A shadow or mirror ray (not a primary one: those start at the camera, the
// origin) whose first step is at its start must come nearer than startLimit of
// the distance there (half of it; no limit in the article's fixed hit test) to
// count a hit: one that starts within the hit threshold of a surface (in a
// crease, or off a surface whose distance grows slower than 1) never hits at
// its own start.
float startHalf = 10000000000.0;

// @part trace-step
float d = @{map}(ro + rd * t@{ray});
startHalf = i == 0 && @{first}t0 > 0.0 ? startLimit(d) : startHalf;

// @part start-unbounded
float t = 0.0;

// @part start-bounded
float tPlane = planesHit(ro, rd);
vec2 span = boundsSpan(ro, rd);
// @slot grid-span
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

// @part about-field
// Through a field's grid (issue 12), bounded as sphere tracing is: the ground planes
// met in closed form, the other finite objects (mapFinite) sphere-traced over the
// span of their bounding spheres, joined to the grid's. The ray walks the grid's
// cells in order (a 3D DDA); in each it meets the objects the cell lists in closed
// form (fieldListEntry): an entry inside the cell, and before any other object can
// be, is the hit. A step never passes the cell's far wall, where the next cell's list
// takes over. An empty cell, with nothing else near, costs one texel; steps counts
// the cells and points where something was evaluated, and only those spend uMaxSteps.

// @part grid-span
vec3 q0 = ro - uFieldOrigin;
vec3 safe = fieldSafeDirection(rd);
vec3 inv = 1.0 / safe;
vec2 box = fieldBoxSpan(q0, inv);
float gridIn = box.x;
float gridOut = box.y;
bool grid = gridIn < gridOut;
// The grid's span joined to the bounding spheres' (theirs is (draw distance, 0) when
// the ray meets none).
span = grid ? vec2(min(span.x, gridIn), max(span.y, gridOut)) : span;

// @part walk-state
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
bool others = fieldOthers();

// @part cell-enter
if (state == 0 && t >= gridIn) {
    cell = fieldCellAt(q0, rd, t, safe, inv, tNext);
    state = 1;
    cellEnd = min(tNext.x, min(tNext.y, tNext.z));
}

// @part step-field
bool evaluated = others;
if (state == 1) {
    vec4 list = fieldRead(uFieldCells, uFieldRows.x, fieldCellIndex(cell));
    if (list.y > 0.0) {
        float hit = fieldListEntry(int(list.x), int(list.y), q0, rd, inv, t0);
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
        cell += ivec3(fieldNextWall(tNext, tDelta)) * stepDir;
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

// @part start-walk
float t0 = length(ro);   // the camera is at the origin: distance already travelled
float tPlane = planesHit(ro, rd);
float tPast = min(tPlane, tMax);
vec3 q0, inv, tNext, tDelta, stride;
float gridIn, tEnd;
int index;

// @part before-walk
if (!fieldWalkStart(ro, rd, tPast, q0, inv, gridIn, tEnd, index, tNext, tDelta, stride)) {
    return tPast;
}
float t = gridIn;

// @part about-cells
// The field's grid walk (as the general walk's) when the field is the only finite
// thing in the scene (beside ground planes): nothing is sphere-traced, so the walk is
// lean, one cell per turn of the loop. The same cells, tests and results.

// @part step-cells
float cellEnd = min(tNext.x, min(tNext.y, tNext.z));
vec4 list = fieldRead(uFieldCells, uFieldRows.x, index);
// (No branch around an empty cell's test: its loop has nothing to do.)
steps += list.y > 0.0 ? 1 : 0;
float hit = fieldListEntry(int(list.x), int(list.y), q0, rd, inv, t0);
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

// @part about-spheres
// The lean grid walk for a field of spheres only: the same cells in the same order
// but the empty ones it jumps across, the same tests and results, in one loop whose
// every turn reads one texel of uFieldWalk (src/render/field.fnl's walk-texture;
// field.walk is this walk on the CPU). A turn either crosses a cell (its texel: the
// one sphere it lists, or where its list starts, or for an empty cell how far on the
// cells are empty, so it jumps there) or meets the next texel of the list of the cell
// it is in (a long list's first is the sphere about its spheres: missed, the cell is
// done). On llvmpipe every turn runs all of its code, branches included, and a loop
// nested in the walk runs its body at least once per turn (measured: even a loop of
// no turns cost a quarter of the frame): one texel and one sphere test per turn is
// the least a cell can cost.
uniform sampler2D uFieldWalk;  // cells, then their lists: a texel each
uniform int uFieldTurns;       // turns a walk can take, at most

// @part spheres-state
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

// @part step-spheres
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

// @part to-draw-distance
// Up to the draw distance: primary and mirror rays.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    return raymarchTo(ro, rd, uDrawDist, steps);
}
