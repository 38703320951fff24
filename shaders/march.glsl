// Sphere tracing as in the article: step along the ray by the distance bound until a
// step falls under the hit threshold, the ray passes the draw distance, or the step
// budget is spent. Returns the distance travelled; steps counts distance evaluations.
// A ray counts as a hit when the returned distance is below the draw distance.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    float t0 = length(ro);   // the camera is at the origin: distance already travelled
    float t = 0.0;
    steps = 0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = map(ro + rd * t);
        steps = i + 1;
        if (d < hitThreshold(t0 + t)) {
            t += d;
            break;
        }
        t += d;
        if (t >= uDrawDist) {
            break;
        }
    }
    return t;
}
