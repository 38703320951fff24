// Surface normal by the tetrahedron technique: four samples at the corners of a
// tetrahedron, k = (1,-1,-1), (-1,-1,1), (-1,1,-1), (1,1,1), give a central-difference
// quality gradient for four distance evaluations. Tap j of kNormalTaps: the sample's
// offset from the point for a step h, and in w its weight in the gradient's sum
// (normal-scene.glsl and normal-crease.glsl take them in a loop from gZero: one copy
// of the distance for all of them).
const int kNormalTaps = 4;

vec3 normalTap(int j, float h, out vec3 w) {
    vec3 k = vec3(float(((j + 3) / 2) % 2), float((j / 2) % 2), float(j % 2)) * 2.0 - 1.0;
    w = k;
    return k * h;
}
