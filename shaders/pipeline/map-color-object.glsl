// The same minimum, also giving the colour of the nearest object (black when no
// object is nearer than the draw distance): mapObject's colour query.
float mapColor(vec3 p, out vec3 color) {
    color = vec3(0.0);
    return mapObject(p, -1, -1, true, color);
}
