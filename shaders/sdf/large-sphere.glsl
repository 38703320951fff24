// Large sphere (radius 1000 or more): exact signed distance without cancellation.
// length(p - c) - r loses all precision near the surface when |c| and r are ~1e6
// (float32 spacing 0.06 there); (|u|^2 - r^2) / (|u| + r) with u = p - c, expanded as
// |p|^2 - 2 p.c + k where k = |c|^2 - r^2 comes from the CPU in double, keeps it.
// s.xyz is the centre (camera-relative), s.w the radius.
float sdLargeSphere(vec3 p, vec4 s, float k) {
    return (dot(p, p) - 2.0 * dot(p, s.xyz) + k) / (length(p - s.xyz) + s.w);
}
