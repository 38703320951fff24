// Grids over instance groups (src/sdf/grid.fnl): a group's rows in a float texture
// about one anchor, and per grid the cells listing the members near each. Every
// texture is 1024 texels wide, one level, nearest filtering (see field.glsl's
// fieldRead for why texture() and a reciprocal of the row count).
uniform sampler2D uBankRows;   // the instance groups' rows, about the anchor
uniform sampler2D uGridCells;  // per cell: first list slot, count, clearance
uniform sampler2D uGridLists;  // per list slot: a member's number
uniform vec3 uBankOrigin;      // the anchor, camera-relative
uniform vec3 uGridRows;        // 1 / rows of the bank, cells and lists textures

vec4 gridTexel(sampler2D s, float rows, int i) {
    return texture(s, (vec2(float(i & 1023), float(i >> 10)) + 0.5) * vec2(1.0 / 1024.0, rows));
}

vec4 bankRow(int i) {
    return gridTexel(uBankRows, uGridRows.x, i);
}

int gridMember(int slot) {
    return int(gridTexel(uGridLists, uGridRows.z, slot).x);
}

// The cell of grid g at q (about the anchor): its list's first slot and count, and
// the lower bound of every member it does not list. Outside the grid: the distance
// to its box plus the reach; inside: the distance to the cell's walls plus the reach,
// or plus the cell's clearance (empty cells around it) where that is more.
float gridCell(int g, vec3 q, out int start, out int count) {
    vec4 a = uGrids[3 * g];      // low corner (about the anchor), reach
    vec4 b = uGrids[3 * g + 1];  // one cell's extents, first cell in uGridCells
    vec3 dims = uGrids[3 * g + 2].xyz;
    vec3 local = q - a.xyz;
    vec3 size = b.xyz * dims;
    vec3 outside = max(max(-local, local - size), 0.0);
    start = 0;
    count = 0;
    if (max(outside.x, max(outside.y, outside.z)) > 0.0) {
        return length(outside) + a.w;
    }
    ivec3 n = ivec3(dims);
    ivec3 c = clamp(ivec3(floor(local / b.xyz)), ivec3(0), n - 1);
    vec3 low = local - vec3(c) * b.xyz;
    vec3 walls = min(low, b.xyz - low);
    vec4 cell = gridTexel(uGridCells, uGridRows.y, int(b.w) + c.x + n.x * (c.y + n.y * c.z));
    start = int(cell.x);
    count = int(cell.y);
    return min(walls.x, min(walls.y, walls.z)) + max(a.w, cell.z);
}
