// An instance group's members in map's queries (src/sdf/strategies/group.fnl): a
// loop over them, each read from the group's bank, or through its grid (grid.glsl)
// over the members the point's cell lists, after folding the others' lower bound
// into d. The slot member holds one member's lines, whose number is i; a group whose
// bank is in a texture reads its rows about uBankOrigin, at pg (slot bank-point).
// Along a march's ray rd, a grid bounds the unlisted members along the ray
// (bound-along), and the march skips a member it is far from by the ray's entry into
// its bounding sphere (skip-along: gridSkip).
// @part loop
for (int i = 0; i < @{count}; i++) {
    // @slot member
}

// @part texture-loop
{
    vec3 pg = p - uBankOrigin;
    // @slot loop
}

// @part grid
{
    // @slot bank-point
    int gridStart;
    int gridCount;
    // @slot bound
    d = min(d, gridBound);
    for (int k = 0; k < gridCount; k++) {
        // @slot skip
        int i = gridMember(gridStart + k);
        // @slot member
    }
}

// @part bound
float gridBound = gridCell(@{grid}, pg, gridStart, gridCount);

// @part bound-along
float gridBound = gridCellAlong(@{grid}, pg, rd, gridStart, gridCount);

// @part skip-along
float gridStep = gridSkip(@{grid}, gridStart + k, pg, rd);
if (gridStep >= 0.0) {
    d = min(d, gridStep);
    continue;
}
