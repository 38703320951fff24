// Step-count glow, the article's: flat object colour on a hit; on a miss a grey that
// grows with the steps the ray took, so near misses glow.
if (t >= uDrawDist) {
    return vec3(float(steps) / 100.0);
}
vec3 surface;
mapColor(ro + rd * t, surface);
return surface;
