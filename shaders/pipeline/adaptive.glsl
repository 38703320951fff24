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

// rd, t: the centre ray and where it hit; n: the normal there (surfaceAt's, which the
// view computed: a second call would be a second copy of it).
bool needsSamples(vec3 rd, float t, vec3 n) {
    vec3 p = rd * t;
    // The whole scene's normal a footprint further along the ray: across an edge or
    // onto another object it turns; past the limb of a curved surface seen edge-on it
    // turns a little, which matters only when the view grazes the surface.
    // Central differences of map, in a loop from gZero: one copy of the scene, where
    // six calls written out were six.
    float e = t / (uProjDist * uResolution.y);
    vec3 q = p + rd * e;
    float h = 0.5 * e;
    vec3 g = vec3(0.0);
    for (int i = gZero; i < 6; i++) {
        int axis = i / 2;
        float s = i == 2 * axis ? 1.0 : -1.0;
        g[axis] += s * map(q + s * axisStep(axis, h));
    }
    vec3 ahead = safeNormalize(g);
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

// One loop over one call of renderSample (GLSL compilers inline every call: four
// calls were four copies of the whole picture's code): turn 0 the centre ray, turn 1
// the second, turns 2 on the grid's, as gridSamples orders and sums them.
vec3 render(vec2 pixel) {
    int grid = kSamples * kSamples;
    vec3 centre = vec3(0.0);
    vec3 sum = vec3(0.0);
    for (int k = uPriorPass > 1.5 && priorEdge(pixel) ? 2 : 0; k < 2 + grid; k++) {
        vec2 at = pixel;
        if (k == 1) {
            at += kSecond;
        } else if (k >= 2) {
            int i = (k - 2) % kSamples;
            int j = (k - 2) / kSamples;
            at += (vec2(float(i), float(j)) + 0.5) / float(kSamples) - 0.5;
        }
        gCentre = k == 0;
        vec3 c = clamp(renderSample(at), 0.0, 1.0);
        gCentre = false;
        if (k == 0) {
            centre = c;
            if (uPriorPass > 0.5 && uPriorPass < 1.5) {
                return centre;
            }
            if (gNeedsSamples) {
                k = 1;  // an edge: on to the grid
            }
        } else if (k == 1) {
            vec3 luma = vec3(0.2126, 0.7152, 0.0722);
            if (abs(dot(c - centre, luma)) <= kContrast) {
                return 0.5 * (centre + c);
            }
        } else {
            sum += c;
        }
    }
    return sum / float(grid);
}
