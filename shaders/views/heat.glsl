// Heat map of the primary ray's step count against the step budget:
// blue (few) through green and yellow to red (all of them).
float h = clamp(float(steps) / float(uMaxSteps), 0.0, 1.0);
return clamp(vec3(1.5 - abs(4.0 * h - 3.0), 1.5 - abs(4.0 * h - 2.0), 1.5 - abs(4.0 * h - 1.0)), 0.0, 1.0);
