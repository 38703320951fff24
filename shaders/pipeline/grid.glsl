// Grids over instance groups (src/sdf/grid.fnl): a group's rows in a float texture
// about one anchor, and per grid the cells listing the members near each. Every
// texture is 1024 texels wide, one level, nearest filtering (see field.glsl's
// fieldRead for why texture() and a reciprocal of the row count).
uniform sampler2D uBankRows;   // the instance groups' rows, about the anchor
uniform sampler2D uGridCells;  // per cell: first list slot, count, clearance
uniform sampler2D uGridLists;  // per list slot: a member's number
uniform sampler2D uGridSpheres;  // per list slot: its member's bounding sphere about the anchor
uniform sampler2D uGridFirsts;  // per list slot: its member's first row in the bank
uniform float uGridFirstRows;  // 1 / rows of uGridFirsts
uniform vec3 uBankOrigin;      // the anchor, camera-relative
uniform vec4 uGridRows;        // 1 / rows of the bank, cells, lists and spheres textures

vec4 gridTexel(sampler2D s, float rows, int i) {
    return texture(s, (vec2(float(i & 1023), float(i >> 10)) + 0.5) * vec2(1.0 / 1024.0, rows));
}

vec4 bankRow(int i) {
    return gridTexel(uBankRows, uGridRows.x, i);
}

// The first row of the member of list slot `slot` (bankRow of its first row): a loop
// over a cell's list reads it without the member's number, which a member whose code
// reads its first row only (a sphere's place and radius) then never reads.
vec4 gridFirst(int slot) {
    return gridTexel(uGridFirsts, uGridFirstRows, slot);
}

int gridMember(int slot) {
    return int(gridTexel(uGridLists, uGridRows.z, slot).x);
}

// How far a march along rd (a unit vector) from q may go before it can meet the member
// of list slot `slot` of grid g, without evaluating it, or -1.0 when q is within the
// grid's reach of the member's bounding sphere (then its distance must be evaluated):
// where the ray enters the sphere (the draw distance when it never does), and at least
// q's distance to it. The sphere sits at the slot: the member's number is read only
// when it is needed.
float gridSkip(int g, int slot, vec3 q, vec3 rd) {
    vec4 s = gridTexel(uGridSpheres, uGridRows.w, slot);
    vec3 oc = q - s.xyz;
    float e = length(oc) - s.w;
    float b = dot(oc, rd);
    vec3 c = oc - b * rd;
    float disc = s.w * s.w - dot(c, c);
    float enter = disc < 0.0 || b > 0.0 ? uDrawDist : -b - sqrt(disc);
    return e > uGrids[3 * g].w ? max(e, enter) : -1.0;
}

// The cell of grid g at q (about the anchor): its list's first slot and count, and
// the lower bound of every member it does not list. Outside the grid: the distance
// to its box plus the reach; inside: the distance to the cell's walls plus the reach,
// or plus the cell's clearance (empty cells around it) where that is more.
// With a ray direction rd (unit; a march's, gridCellAlong), also how far the ray may
// go before it can meet an unlisted member: to the grid's box from outside (every
// member lies a reach inside it), to the cell's far wall from inside (every unlisted
// member is a reach beyond the cell); the bound is the larger of the two. Without
// one (rd = 0), the bound alone.
float gridCellAlong(int g, vec3 q, vec3 rd, out int start, out int count) {
    vec4 a = uGrids[3 * g];      // low corner (about the anchor), reach
    vec4 b = uGrids[3 * g + 1];  // one cell's extents, first cell in uGridCells
    vec3 dims = uGrids[3 * g + 2].xyz;  // cells along each axis
    vec3 local = q - a.xyz;
    vec3 size = b.xyz * dims;
    vec3 outside = max(max(-local, local - size), 0.0);
    // 1 / |rd| along each axis, huge where the ray does not move along it.
    vec3 inv = 1.0 / max(abs(rd), vec3(0.000001));
    bool along = dot(rd, rd) > 0.0;
    start = 0;
    count = 0;
    if (max(outside.x, max(outside.y, outside.z)) > 0.0) {
        float bound = length(outside) + a.w;
        if (along) {
            // The slab test: where the ray enters the grid's box (never, at most
            // the draw distance).
            vec3 safe = mix(rd, vec3(0.000001), lessThan(abs(rd), vec3(0.000001)));
            vec3 ta = -local / safe;
            vec3 tb = (size - local) / safe;
            vec3 tNear = min(ta, tb);
            vec3 tFar = max(ta, tb);
            float enter = max(tNear.x, max(tNear.y, tNear.z));
            float leave = min(tFar.x, min(tFar.y, tFar.z));
            bound = max(bound, enter <= leave && leave > 0.0 ? enter : uDrawDist);
        }
        return bound;
    }
    ivec3 n = ivec3(dims);
    ivec3 c = clamp(ivec3(floor(local / b.xyz)), ivec3(0), n - 1);
    vec3 low = local - vec3(c) * b.xyz;
    vec3 high = b.xyz - low;
    vec3 walls = min(low, high);
    vec4 cell = gridTexel(uGridCells, uGridRows.y, int(b.w) + c.x + n.x * (c.y + n.y * c.z));
    start = int(cell.x);
    count = int(cell.y);
    float bound = min(walls.x, min(walls.y, walls.z)) + max(a.w, cell.z);
    if (along) {
        vec3 ahead = mix(low, high, step(0.0, rd)) * inv;
        bound = max(bound, min(ahead.x, min(ahead.y, ahead.z)));
    }
    return bound;
}

float gridCell(int g, vec3 q, out int start, out int count) {
    return gridCellAlong(g, q, vec3(0.0), start, count);
}
