// Surface normal by central differences: second-order accurate, six distance
// evaluations, a step h forward and back along each axis. Tap j of kNormalTaps: the
// sample's offset from the point, and in w its weight in the gradient's sum (see
// tetrahedron.glsl).
const int kNormalTaps = 6;

vec3 normalTap(int j, float h, out vec3 w) {
    int axis = j / 2;
    float s = j == 2 * axis ? 1.0 : -1.0;
    w = axisStep(axis, s);
    return s * axisStep(axis, h);
}
