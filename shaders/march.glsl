// Sphere tracing as in the article: step along the ray by the distance bound until a
// step is shorter than the hit epsilon, the ray passes the draw distance, or the step
// budget is spent. Returns the distance travelled; steps counts distance evaluations.
// A ray counts as a hit when the returned distance is below the draw distance.
float raymarch(vec3 ro, vec3 rd, out int steps) {
    float t = 0.0;
    steps = 0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = map(ro + rd * t);
        t += d;
        steps = i + 1;
        if (d < uEpsilon || t >= uDrawDist) {
            break;
        }
    }
    return t;
}
