// A field: many small objects in float textures, found through a uniform grid
// (src/render/field.fnl builds both): spheres and boxes, met in closed form, and
// marched members (field-primitives.glsl, compiled in when the field holds some).
// Coordinates in the textures are field-local: the grid's low corner is the origin,
// sent camera-relative each frame.
uniform sampler2D uFieldCells;    // per cell: first record, record count
uniform sampler2D uFieldRecords;  // per record: centre, radius; half extents, object
uniform sampler2D uFieldObjects;  // per object: its record; colour; (marched) frame, numbers
uniform vec3 uFieldOrigin;        // the grid's low corner (camera-relative)
uniform vec3 uFieldSize;          // the grid's extents
uniform vec3 uFieldCell;          // one cell's extents
uniform vec3 uFieldDims;          // cells along each axis
uniform float uFieldReach;        // a listed object's box grown by this meets the cell
uniform int uFieldCrossings;      // cells a ray can cross, at most
uniform vec4 uFieldRows;          // 1 / rows of the cells, records, objects, walk textures

// Texel i of a field texture (1024 texels wide, row after row; `rows` is 1 over its
// row count), read at its centre. Every field texture has one level and nearest
// filtering, so texture() returns the texel exactly, derivatives or not; on llvmpipe
// it is cheaper than texelFetch, whose explicit level makes it work out a level and a
// size per pixel, and a uniform's reciprocal cheaper than dividing by textureSize.
vec4 fieldRead(sampler2D s, float rows, int i) {
    return texture(s, (vec2(float(i & 1023), float(i >> 10)) + 0.5) * vec2(1.0 / 1024.0, rows));
}

// The one distance of every field object, the round-box primitive's (exact): a
// sphere has no half extents, a box no radius.
float sdFieldShape(vec3 q, vec4 centre, vec3 halfSize) {
    return sdRoundBox(q - centre.xyz, halfSize, centre.w);
}

// @slot marched

// The distance at the field-local q of the member whose record is a, b.
float fieldMemberDistance(vec3 q, vec4 a, vec4 b) {
    // @slot member-distance
}

// A ray direction whose tiny components are replaced by kFieldTiny: its reciprocal
// along an axis the ray does not move along is huge, not an infinity.
vec3 fieldSafeDirection(vec3 rd) {
    return mix(rd, vec3(kFieldTiny), lessThan(abs(rd), vec3(kFieldTiny)));
}

// Where the ray q0 + rd t (field-local; inv the reciprocal of its safe direction) is
// inside the grid's box: entry (at least 0) and exit, by the slab test.
vec2 fieldBoxSpan(vec3 q0, vec3 inv) {
    vec3 ta = -q0 * inv;
    vec3 tb = (uFieldSize - q0) * inv;
    vec3 tNear = min(ta, tb);
    vec3 tFar = max(ta, tb);
    return vec2(max(max(tNear.x, tNear.y), max(tNear.z, 0.0)), min(tFar.x, min(tFar.y, tFar.z)));
}

int fieldCellIndex(ivec3 c) {
    ivec3 n = ivec3(uFieldDims);
    return c.x + n.x * (c.y + n.y * c.z);
}

// The cell the ray q0 + rd t (field-local; `safe` its safe direction, `inv` the
// reciprocal of that) is in at t, clamped to the grid, and where the ray next crosses
// a wall of it along each axis (tNext): where a walk enters the grid.
ivec3 fieldCellAt(vec3 q0, vec3 rd, float t, vec3 safe, vec3 inv, out vec3 tNext) {
    ivec3 cell = clamp(ivec3(floor((q0 + rd * t) / uFieldCell)), ivec3(0), ivec3(uFieldDims) - 1);
    tNext = ((vec3(cell) + step(vec3(0.0), safe)) * uFieldCell - q0) * inv;
    return cell;
}

// A walk's step to the next wall along the ray: the axis (or axes, at a tie) whose
// wall comes first (1 in m), whose crossing moves on by tDelta.
vec3 fieldNextWall(inout vec3 tNext, vec3 tDelta) {
    vec3 m = step(tNext, min(tNext.yzx, tNext.zxy));
    tNext += m * tDelta;
    return m;
}

// The start of a lean walk (march.glsl's start-walk, before-walk): the ray
// ro + rd t, field-local q0 + rd t with `inv` the reciprocal of its safe direction,
// is in the grid from gridIn to tEnd (its exit, or tPast if sooner); false when that
// span is empty. The cell it enters, by number (`index`); where it next crosses a wall
// along each axis (tNext), how far apart the crossings are (tDelta), and what a step
// along each axis adds to the cell's number (stride).
bool fieldWalkStart(vec3 ro, vec3 rd, float tPast, out vec3 q0, out vec3 inv, out float gridIn,
                    out float tEnd, out int index, out vec3 tNext, out vec3 tDelta,
                    out vec3 stride) {
    q0 = ro - uFieldOrigin;
    vec3 safe = fieldSafeDirection(rd);
    inv = 1.0 / safe;
    vec2 box = fieldBoxSpan(q0, inv);
    gridIn = box.x;
    tEnd = min(box.y, tPast);
    ivec3 cell = fieldCellAt(q0, rd, gridIn, safe, inv, tNext);
    tDelta = uFieldCell * abs(inv);
    index = fieldCellIndex(cell);
    stride = sign(safe) * vec3(1.0, uFieldDims.x, uFieldDims.x * uFieldDims.y);
    return gridIn < tEnd;
}

// A lean walk's step into the next cell, by number.
void fieldNextCell(inout vec3 tNext, inout int index, vec3 tDelta, vec3 stride) {
    index += int(dot(fieldNextWall(tNext, tDelta), stride));
}

// The nearest object listed in cell `cell` to the field-local point q, skipping
// object `skip`: its distance (the draw distance when none) and number in `best`.
// Ties go to the earlier record, as in the reference.
float fieldCellDistance(int cell, vec3 q, int skip, out int best) {
    vec4 list = fieldRead(uFieldCells, uFieldRows.x, cell);
    int start = 2 * int(list.x);
    int count = int(list.y);
    float d = uDrawDist;
    best = -1;
    for (int k = 0; k < count; k++) {
        vec4 a = fieldRead(uFieldRecords, uFieldRows.y, start + 2 * k);
        vec4 b = fieldRead(uFieldRecords, uFieldRows.y, start + 2 * k + 1);
        float di = fieldMemberDistance(q, a, b);
        int object = int(b.w);
        if (di < d && object != skip) {
            d = di;
            best = object;
        }
    }
    return d;
}

// Where the ray q0 + rd t (field-local, rd a unit vector, inv its reciprocal) first
// enters a field object (centre and radius a, half extents h), at t >= 0: the draw
// distance when it misses. In closed form: a sphere from the ray's point of closest
// approach (no cancellation for a far ray), a box by the slab test. A ray starting
// inside enters at 0.
float fieldSphereEntry(vec3 q0, vec3 rd, vec4 a) {
    vec3 oc = q0 - a.xyz;
    float b = dot(oc, rd);
    vec3 c = oc - b * rd;
    float disc = a.w * a.w - dot(c, c);
    float s = sqrt(max(disc, 0.0));
    return (disc < 0.0 || s - b < 0.0) ? uDrawDist : max(-b - s, 0.0);
}

float fieldBoxEntry(vec3 q0, vec3 inv, vec4 a, vec3 h) {
    vec3 t1 = (a.xyz - h - q0) * inv;
    vec3 t2 = (a.xyz + h - q0) * inv;
    vec3 tn = min(t1, t2);
    vec3 tf = max(t1, t2);
    float near = max(max(tn.x, tn.y), tn.z);
    float far = min(min(tf.x, tf.y), tf.z);
    return (near > far || far < 0.0) ? uDrawDist : max(near, 0.0);
}

// The ray's first entry into an object of the list of `count` records from `start`
// (t0: the distance the ray has travelled to q0, for a marched member's hit test).
// (Only the kinds the field holds are compiled in: on llvmpipe code behind a branch
// runs for every pixel.)
float fieldListEntry(int start, int count, vec3 q0, vec3 rd, vec3 inv, float t0) {
    float t = uDrawDist;
    for (int k = 0; k < count; k++) {
        int r = 2 * (start + k);
        vec4 a = fieldRead(uFieldRecords, uFieldRows.y, r);
        // @slot entry
    }
    return t;
}

// The field's distance at p (camera-relative): exact within the reach of p's cell, a
// lower bound beyond it (the cell's walls plus the reach: nothing unlisted is nearer).
float fieldMap(vec3 p, int skip, out int best) {
    vec3 q = p - uFieldOrigin;
    vec3 outside = max(max(-q, q - uFieldSize), 0.0);
    best = -1;
    if (max(outside.x, max(outside.y, outside.z)) > 0.0) {
        return length(outside) + uFieldReach;
    }
    ivec3 c = clamp(ivec3(floor(q / uFieldCell)), ivec3(0), ivec3(uFieldDims) - 1);
    vec3 low = q - vec3(c) * uFieldCell;
    vec3 high = uFieldCell - low;
    vec3 walls = min(low, high);
    float wall = min(walls.x, min(walls.y, walls.z)) + uFieldReach;
    return min(fieldCellDistance(fieldCellIndex(c), q, skip, best), wall);
}

// One object's distance, by number.
float fieldObject(vec3 p, int object) {
    vec4 a = fieldRead(uFieldObjects, uFieldRows.z, kFieldObjectTexels * object);
    vec4 b = fieldRead(uFieldObjects, uFieldRows.z, kFieldObjectTexels * object + 1);
    return fieldMemberDistance(p - uFieldOrigin, a, b);
}

vec3 fieldColor(int object) {
    return fieldRead(uFieldObjects, uFieldRows.z, kFieldObjectTexels * object + 2).rgb;
}

// The exact normal of a field object at p: its distance's gradient, which is its
// inner box's (gradBox, the box descriptor's; a sphere is a box of no extent).
vec3 fieldNormal(vec3 p, int object) {
    vec4 a = fieldRead(uFieldObjects, uFieldRows.z, kFieldObjectTexels * object);
    vec3 h = fieldRead(uFieldObjects, uFieldRows.z, kFieldObjectTexels * object + 1).xyz;
    return gradBox(p - uFieldOrigin - a.xyz, h);
}
