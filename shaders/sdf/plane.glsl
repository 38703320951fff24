// Ground plane z = h, normal +z: exact signed distance (negative below).
float sdPlane(vec3 p, float h) {
    return p.z - h;
}
