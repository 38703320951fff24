// Hit test by pixel footprint: a step shorter than epsilon times the width one pixel
// covers at that distance is a hit (epsilon is a fraction of a pixel).
float hitThreshold(float dist) {
    return uEpsilon * dist / (uProjDist * uResolution.y);
}
