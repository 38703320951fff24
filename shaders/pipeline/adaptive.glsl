// @part tests
// Adaptive supersampling: one ray through the pixel's centre first, and only where
// what it met says the pixel holds an edge, kSamples x kSamples rays on the grid inside
// it (as full supersampling; the centre ray is not counted). An edge: the primary ray
// hit at a grazing angle (the silhouette of a smooth object); or the whole scene's
// normal over the pixel's footprint turns away from the surface's own (a crease, a
// corner, another object within the footprint); or, tested in render(), a second ray
// in the pixel disagrees with the centre's.
// @slot constants
bool gCentre = false;        // renderSample is tracing the centre ray
bool gNeedsSamples = false;  // and found an edge

bool needsSamples(vec3 rd, float t) {
    if (t >= uDrawDist) {
        return false;
    }
    vec3 p = rd * t;
    vec3 surface;
    mapColor(p, surface);  // first: calcNormal may read the object it found
    vec3 n = calcNormal(p);
    // The whole scene's normal a footprint further along the ray: across an edge or
    // onto another object it turns; past the limb of a curved surface seen edge-on it
    // turns a little, which matters only when the view grazes the surface.
    float e = t / (uProjDist * uResolution.y);
    vec3 q = p + rd * e;
    vec2 h = vec2(0.5 * e, 0.0);
    vec3 ahead = safeNormalize(vec3(map(q + h.xyy) - map(q - h.xyy),
                                    map(q + h.yxy) - map(q - h.yxy),
                                    map(q + h.yyx) - map(q - h.yyx)));
    float turn = 1.0 - dot(n, ahead);
    float facing = dot(n, -rd);
    return turn > kEdgeTurn || (facing < kGrazing && turn > kLimbTurn);
}

// @part render
// Where the centre ray finds no edge, a second ray elsewhere in the pixel: what no
// test on the centre ray sees (an edge in a mirror, a shadow's edge, an object smaller
// than the pixel) mostly makes the two differ, and then the pixel gets the grid too.
// Where they agree, the pixel is their mean.
vec3 render(vec2 pixel) {
    gCentre = true;
    vec3 centre = clamp(renderSample(pixel), 0.0, 1.0);
    gCentre = false;
    if (!gNeedsSamples) {
        vec3 second = clamp(renderSample(pixel + kSecond), 0.0, 1.0);
        vec3 luma = vec3(0.2126, 0.7152, 0.0722);
        if (abs(dot(second - centre, luma)) <= kContrast) {
            return 0.5 * (centre + second);
        }
    }
    return gridSamples(pixel);
}
