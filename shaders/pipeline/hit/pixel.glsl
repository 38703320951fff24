// Hit test by pixel footprint: a step shorter than epsilon times the width one pixel
// covers at that distance is a hit (epsilon is a fraction of a pixel).
float hitThreshold(float dist) {
    return uEpsilon * dist / (uProjDist * uResolution.y);
}

// The nearest a shadow or mirror ray may come to count a hit, given the distance d at
// its start (see march.glsl's startHalf): half of it, so the ray's own start is never
// a hit; a start inside a solid (d <= 0) is left alone.
float startLimit(float d) {
    return d > 0.0 ? 0.5 * d : 10000000000.0;
}
