// @part tests
// Adaptive supersampling: one ray through the pixel's centre first, and only where
// what it met says the pixel holds an edge, kSamples x kSamples rays on the grid inside
// it (as full supersampling; the centre ray is not counted). An edge: the primary ray
// took many steps (it grazed a surface: near misses, silhouettes); it hit at a grazing
// angle (the silhouette of a smooth object); or the whole scene's normal over the
// pixel's footprint turns away from the surface's own (a crease, a corner, another
// object within the footprint).
// @slot constants
bool gCentre = false;        // renderSample is tracing the centre ray
bool gNeedsSamples = false;  // and found an edge

bool needsSamples(vec3 rd, float t, int steps) {
    if (steps >= kEdgeSteps) {
        return true;
    }
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
vec3 render(vec2 pixel) {
    gCentre = true;
    vec3 centre = clamp(renderSample(pixel), 0.0, 1.0);
    gCentre = false;
    if (!gNeedsSamples) {
        return centre;
    }
    return gridSamples(pixel);
}
