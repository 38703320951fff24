// @part tests
// Adaptive supersampling: one ray through the pixel's centre first, and only where
// what it met says the pixel holds an edge, kSamples x kSamples rays on the grid inside
// it (as full supersampling; the centre ray is not counted). An edge: the primary ray
// hit at a grazing angle (the silhouette of a smooth object); or the whole scene's
// normal over the pixel's footprint turns away from the surface's own (a crease, a
// corner, another object within the footprint); or, tested in render(), a second ray
// in the pixel disagrees with the centre's.
//
// A finished picture (the player's still, --render, --record) also has the picture of
// the centre rays alone (the player's full-resolution one; --render draws it first
// with this shader, uPriorPass 1): a pixel whose centre ray's luma differs from a
// neighbour's by more than kContrast gets the grid at once. That sees what the
// pixel's own two rays cannot: an edge or a thin feature that crosses the pixel
// between them (building edges in city, flutes in colonnade, tile joints in a mirror).
// @slot constants
uniform sampler2D uPrior;  // the centre rays' picture, read in pass 2
uniform float uPriorPass;  // 0: no such picture; 1: draw it (centre rays only); 2: read it
bool gCentre = false;        // renderSample is tracing the centre ray
bool gNeedsSamples = false;  // and found an edge

bool needsSamples(vec3 rd, float t) {
    if (t >= uDrawDist) {
        return false;
    }
    vec3 p = rd * t;
    vec3 surface;
    vec3 n = surfaceAt(p, surface);
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
bool priorEdge(vec2 pixel) {
    // pixel is the pixel's centre, y down: so are the prior's texture coordinates.
    vec2 texel = 1.0 / uResolution;
    vec3 luma = vec3(0.2126, 0.7152, 0.0722);
    float c = dot(texture(uPrior, pixel * texel).rgb, luma);
    const vec2 around[8] = vec2[8](vec2(-1.0, -1.0), vec2(0.0, -1.0), vec2(1.0, -1.0),
                                   vec2(-1.0, 0.0), vec2(1.0, 0.0),
                                   vec2(-1.0, 1.0), vec2(0.0, 1.0), vec2(1.0, 1.0));
    float m = 0.0;
    for (int k = 0; k < 8; k++) {
        m = max(m, abs(dot(texture(uPrior, (pixel + around[k]) * texel).rgb, luma) - c));
    }
    return m > kContrast;
}

vec3 render(vec2 pixel) {
    if (uPriorPass > 1.5 && priorEdge(pixel)) {
        return gridSamples(pixel);
    }
    gCentre = true;
    vec3 centre = clamp(renderSample(pixel), 0.0, 1.0);
    gCentre = false;
    if (uPriorPass > 0.5 && uPriorPass < 1.5) {
        return centre;
    }
    if (!gNeedsSamples) {
        vec3 second = clamp(renderSample(pixel + kSecond), 0.0, 1.0);
        vec3 luma = vec3(0.2126, 0.7152, 0.0722);
        if (abs(dot(second - centre, luma)) <= kContrast) {
            return 0.5 * (centre + second);
        }
    }
    return gridSamples(pixel);
}
