// Mirror bounces for scenes whose materials are part mirrors: the article's blend (a
// hit adds its colour at half its lightness and scales by 0.66; a miss blends in the
// environment and stops), mixed with the colour before the bounce by the mirror
// amount of the surface the ray leaves (1: the article's bounce, 0: none). mapColor
// leaves the mirror amount of what it found in gMirror.
vec3 dir = rd;
float mirror = gMirror;
for (int bounce = 1; bounce <= uReflections; bounce++) {
    if (mirror <= 0.0) {
        break;
    }
    vec3 before = color;
    vec3 r = dir - 2.0 * dot(dir, n) * n;
    vec3 origin = p + n * (2.0 * normalDelta(p));
    int bounceSteps;
    float tr = raymarch(origin, r, bounceSteps);
    if (tr >= uDrawDist) {
        color = mix(before, (color + uEnvColor / float(bounce)) * 0.5, mirror);
        break;
    }
    p = origin + r * tr;
    n = calcNormal(p);
    dir = r;
    vec3 hitColor;
    mapColor(p, hitColor);
    float nextMirror = gMirror;
    color = mix(before, (color + hitColor * lightness(p, n) * 0.5) * 0.66, mirror);
    mirror = nextMirror;
}
