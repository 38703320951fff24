// Hard shadow, ending at the light (with bounds, issue 11): a ray toward the light from
// just above the surface halves the lightness when it meets something before the
// light; an object behind the light casts no shadow. A surface facing away is dark
// already.
if (lambert > 0.0) {
    int shadowSteps;
    float ts = raymarchTo(p + n * (2.0 * normalDelta(p)), l, lightDist, shadowSteps);
    if (ts < lightDist) {
        lambert *= 0.5;
    }
}
