// Surface normal by one-sided differences, the article's: the gradient between p and
// p minus a small step h along each axis. Four distance evaluations: tap 0 the point
// itself, in every component, taps 1-3 a step back along each axis. Tap j of
// kNormalTaps: the sample's offset from the point, and in w its weight in the
// gradient's sum (see tetrahedron.glsl).
const int kNormalTaps = 4;

vec3 normalTap(int j, float h, out vec3 w) {
    w = j == 0 ? vec3(1.0) : -axisStep(j - 1, 1.0);
    return j == 0 ? vec3(0.0) : -axisStep(j - 1, h);
}
