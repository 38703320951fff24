// Axis-aligned box: exact signed distance (negative inside, unlike the article's
// unsigned one). c is the centre (camera-relative), h the half extents.
float sdBox(vec3 p, vec3 c, vec3 h) {
    vec3 q = abs(p - c) - h;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}
