// Soft shadows (modern model; Quilez's improved penumbra estimate): marching toward
// the light, each pair of steps bounds how close the ray passed to a surface, and the
// light is visible in proportion to the narrowest closest approach over the penumbra
// width there (softness times the distance). Free of the banding of the plain
// estimate. A light of softness 0 casts a hard shadow: that march is compiled in only
// when a light of the scene may have softness 0 (the slot is empty otherwise). The
// march may take another feature's distance samples first (plan.lighting's :taps,
// ambient occlusion's: occlusion-taps.glsl), as turns before 0 of its loop.
float visibility(vec3 o, vec3 l, float reach, float softness@{params}) {
    // @slot hard-shadow
    float t0 = length(o);
    float seen = 1.0;
    float t = 0.0;
    float hPrev = 10000000000.0;
    float hePrev = hPrev;
    // As the marches (march.glsl): a hit must come nearer than startLimit of the
    // start's distance, so the ray's own start is never one.
    float startHalf = 10000000000.0;
    // @slot soft-span
    // @slot taps-start
    for (int i = @{first-turn}; i < kShadowSteps; i++) {
        // @slot turn
        // @slot soft-map
        // @slot take
        startHalf = i == 0 && t == 0.0 ? startLimit(h) : startHalf;
        if (h < min(hitThreshold(t0 + t), startHalf)) {
            // @slot blocked
        }
        // The penumbra reads the field as an estimate (he: see gEstimate); where
        // that is not the step (hPrev), the two spheres' chord is taken at its own
        // place: the slot writes the form for it.
        // @slot soft-along
        float closest = sqrt(max(he * he - y * y, 0.0));
        // The closest approach lies at t - y along the ray. At or behind the origin it
        // is the surface the ray leaves (a ray along the normal has y = t + the start
        // offset, and closest 0 up to rounding): no occluder, so no darkening.
        float along = t - y;
        if (along > 0.0) {
            seen = min(seen, closest / (softness * along));
        }
        hPrev = h;
        hePrev = he;
        t += h;
        if (t >= reach) {
            break;
        }
    }
    // @slot taps-end
    seen = clamp(seen, 0.0, 1.0);
    return seen * seen * (3.0 - 2.0 * seen);
}
