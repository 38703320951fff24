// The same minimum, also giving the colour of the nearest object (black when no
// object is nearer than the draw distance). Called once per hit, not per step.
float mapColor(vec3 p, out vec3 color) {
    float d = uDrawDist;
    color = vec3(0.0);
    // @slot color-terms
    return d;
}
