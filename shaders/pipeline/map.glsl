// Distance to the nearest surface. Like the article's distance estimator it starts
// from the draw distance, so no distance is ever larger than that.
float map(vec3 p) {
    float d = uDrawDist;
    // @slot distance-terms
    return d;
}
