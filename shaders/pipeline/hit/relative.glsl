// Hit test relative to the distance travelled: a step shorter than epsilon times the
// distance from the camera is a hit, so far surfaces need no more float precision than
// they have.
float hitThreshold(float dist) {
    return uEpsilon * dist;
}
