// Hit test, the article's: a step shorter than epsilon world units is a hit, at any
// distance. dist is the distance from the camera along the ray's path.
float hitThreshold(float dist) {
    return uEpsilon;
}
