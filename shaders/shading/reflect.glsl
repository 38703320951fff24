// Mirror bounces, the article's colour blend: a hit adds its colour at half its
// lightness and scales by 0.66; a miss blends in the environment and stops.
vec3 dir = rd;
// @slot mirror-start
for (int bounce = 1; bounce <= uReflections; bounce++) {
    // @slot mirror-before
    vec3 r = dir - 2.0 * dot(dir, n) * n;
    vec3 origin = p + n * (2.0 * normalDelta(p));
    int bounceSteps;
    float tr = raymarch(origin, r, bounceSteps);
    if (tr >= uDrawDist) {
        color = (color + uEnvColor / float(bounce)) * 0.5;
        // @slot mirror-mix
        break;
    }
    p = origin + r * tr;
    vec3 hitColor;
    n = surfaceAt(p, hitColor);
    dir = r;
    color = (color + hitColor * lightness(p, n) * 0.5) * 0.66;
    // @slot mirror-mix
    // @slot mirror-next
}
