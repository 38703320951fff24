// Sphere: exact signed distance. s.xyz is the centre (camera-relative), s.w the radius.
float sdSphere(vec3 p, vec4 s) {
    return length(p - s.xyz) - s.w;
}
