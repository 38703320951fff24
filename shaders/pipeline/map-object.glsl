// The distance to one object alone: the one the last mapColor call found nearest
// (gObject). Normals differentiate it, so a point where two objects meet gets the
// normal of the surface it lies on, not one pointing between them (with the whole
// scene's distance, a mirror bounce from such a crease lights a single pixel).
// With no object found (gObject -1) no case matches and the whole scene's distance is
// taken: one copy of map for both.
float mapObject(vec3 p) {
    // @slot object-terms
    return map(p);
}

// The distance to every object but that one: what a point on it has beside it.
float mapOthers(vec3 p) {
    float d = uDrawDist;
    // @slot others-terms
    return d;
}
