// Hard shadow, ending at the light (with bounds, issue 11): a ray toward the light from
// just above the surface halves the lightness when it meets something before the
// light; an object behind the light casts no shadow. A surface facing away is dark
// already.
// A surface within the normal offset of the light does not shadow it (a light on
// a surface would otherwise flip between lit and shadowed); nothing past the draw
// distance does either, as in the article.
if (lambert > 0.0) {
    int shadowSteps;
    float reach = min(lightDist - 2.0 * normalDelta(uLightPos), uDrawDist);
    float ts = raymarchTo(p + n * (2.0 * normalDelta(p)), l, reach, shadowSteps);
    if (ts < reach) {
        lambert *= 0.5;
    }
}
