// A field's members in map's queries (src/sdf/strategies/field.fnl), through its
// grid (field.glsl's fieldMap: the nearest listed member, `best`, -1 outside the
// grid). minimum: the field's part of a minimum, skipping member @{skip}; color: the
// nearest member's colour (its members are matte: the mirror amount and material
// stay), and in slot object its number in gObject.
// @part minimum
{
    int best;
    d = min(d, fieldMap(p, @{skip}, best));
}

// @part color
{
    int best;
    float di = fieldMap(p, -1, best);
    if (di < d) {
        d = di;
        color = best >= 0 ? fieldColor(best) : vec3(0.0);
        // @slot object
    }
}
