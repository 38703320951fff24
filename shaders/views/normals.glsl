// Normals view: the surface normal mapped from [-1, 1] to [0, 1]; black on a miss.
if (t >= uDrawDist) {
    return vec3(0.0);
}
// @slot normal
