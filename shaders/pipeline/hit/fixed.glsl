// Hit test, the article's: a step shorter than epsilon world units is a hit, at any
// distance. dist is the distance from the camera along the ray's path.
float hitThreshold(float dist) {
    return uEpsilon;
}

// The nearest a shadow or mirror ray may come to count a hit, given the distance d at
// its start (see march.glsl's startHalf): the article's test leaves the start alone.
float startLimit(float d) {
    return 10000000000.0;
}
