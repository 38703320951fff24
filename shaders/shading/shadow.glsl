// Hard shadow: a ray toward the light from just above the surface halves the
// lightness when it hits anything. A surface facing away is dark already.
if (lambert > 0.0) {
    int shadowSteps;
    float ts = raymarch(p + n * (2.0 * normalDelta(p)), l, shadowSteps);
    if (ts < uDrawDist) {
        lambert *= 0.5;
    }
}
