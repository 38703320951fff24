// Ambient occlusion's samples as the first turns of the first light's soft shadow
// march (plan.lighting's :taps; shadow-soft.glsl's slots): turns -kOcclusionTaps to
// -1 read the scene's distance, half-spaces included (its estimate: he), at the
// samples' points p + n h; turn 0 on is the shadow's. The light's loop calls it with
// taps = kOcclusionTaps for the first light, 0 for the others (their loops run no
// sample), and occ, the view's, takes the samples' share.

// @part params
, int taps, vec3 p, vec3 n, inout float occ

// @part start
vec3 taken = vec3(0.0, 1.0, 0.0);  // the samples' sums (occlusionTake)

// @part turn
bool tap = i < 0;
if (i == 0 && t >= reach) {
    break;  // a plane hides the light (reach -1), or the span ends before it starts
}
float tapHeight = occlusionHeight(i + taps + 1);
vec3 q = tap ? p + n * tapHeight : o + l * t;

// @part take
if (tap) {
    taken = occlusionTake(taken, tapHeight, he);
    continue;
}

// @part end
if (taps > 0) {
    occ *= occlusionOf(taken);
}
