// Hit test relative to the distance travelled: a step shorter than epsilon times the
// distance from the camera is a hit, so far surfaces need no more float precision than
// they have.
float hitThreshold(float dist) {
    return uEpsilon * dist;
}

// The nearest a shadow or mirror ray may come to count a hit, given the distance d at
// its start (see march.glsl's startHalf): half of it, so the ray's own start is never
// a hit; a start inside a solid (d <= 0) is left alone.
float startLimit(float d) {
    return d > 0.0 ? 0.5 * d : 10000000000.0;
}
