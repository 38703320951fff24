// Normals view: the surface normal mapped from [-1, 1] to [0, 1]; black on a miss.
if (t >= uDrawDist) {
    return vec3(0.0);
}
// @slot nearest
return calcNormal(ro + rd * t) * 0.5 + 0.5;
