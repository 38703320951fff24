// @part grid
// Supersampling: kSamples x kSamples rays per pixel on a regular grid inside it, each
// clamped to the displayable range (as one sample's colour is when it is stored) and
// averaged.
vec3 gridSamples(vec2 pixel) {
    vec3 sum = vec3(0.0);
    for (int j = 0; j < kSamples; j++) {
        for (int i = 0; i < kSamples; i++) {
            vec2 offset = (vec2(float(i), float(j)) + 0.5) / float(kSamples) - 0.5;
            sum += clamp(renderSample(pixel + offset), 0.0, 1.0);
        }
    }
    return sum / float(kSamples * kSamples);
}

// @part render
// Every pixel gets the grid.
vec3 render(vec2 pixel) {
    return gridSamples(pixel);
}
