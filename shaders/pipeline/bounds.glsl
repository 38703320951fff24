// What a bounded march reads (src/render/bounds.fnl): the finite objects' distance,
// the nearest half-space along a ray, and the span of the bounding spheres (uBounds)
// a ray is inside. codegen picks the parts the plan needs and fills their slots.
//
// soft-span is a soft shadow ray's start with bounds (the soft-span slot of its
// march): a plane before the light hides it; else it marches the finite objects
// only over the span of their bounding spheres grown by the penumbra width there
// (softness times the distance, so a sphere q away with radius r grows by
// s (q + r) / (1 - s): no farther point of the ray can be darkened by it); a ray
// that meets none is lit. From a softness of 0.5 on, the whole ray.
// @part map-finite
// The finite objects only: the half-spaces are met in closed form by planesHit.
float mapFinite(vec3 p) {
    float d = uDrawDist;
    // @slot distance-terms
    return d;
}

// @part map-some
// The finite objects, and the half-spaces too where `planes` holds: map and mapFinite
// written once, for a soft shadow march that takes ambient occlusion's samples too
// (occlusion-taps.glsl). Every other call passes a constant, which the compiler
// folds.
float mapSome(vec3 p, bool planes) {
    float d = uDrawDist;
    // @slot distance-terms
    return d;
}

// @part map-finite-some
// The finite objects only: the half-spaces are met in closed form by planesHit.
float mapFinite(vec3 p) {
    return mapSome(p, false);
}

// @part map-some-all
// Distance to the nearest surface (see map.glsl).
float map(vec3 p) {
    return mapSome(p, true);
}

// @part planes-hit
// The nearest half-space (a ground plane, solid below) along the ray: 0 from inside
// it, the draw distance when the ray meets none.
float planesHit(vec3 ro, vec3 rd) {
    float t = uDrawDist;
    // @slot plane-terms
    return t;
}

// @part spheres-texture
// The bounding spheres from an image (the interpreter's: their count is not in the
// text): texel 0 holds the count, texels 1 to n the spheres, a line @{width} wide.
uniform sampler2D uBounds;  // their count, then the bounding spheres of the finite objects (camera-relative)

int boundsCount() {
    return int(texelFetch(uBounds, ivec2(0, 0), 0).x);
}

vec4 boundsSphere(int i) {
    return texelFetch(uBounds, ivec2((i + 1) % @{width}, (i + 1) / @{width}), 0);
}

// @part span
// Where the ray is inside some bounding sphere: the first entry and the last exit,
// or (draw distance, 0) when it meets none. From the point of closest approach, so
// a far ray passing near a small sphere loses nothing to cancellation.
vec2 boundsSpan(vec3 ro, vec3 rd) {
    float enter = uDrawDist;
    float exit = 0.0;
    // @slot spheres
    return vec2(enter, min(exit, uDrawDist));
}

// @part span-loop
for (int i = 0; i < @{count}; i++) {
    vec3 q = ro - @{sphere}.xyz;
    float b = dot(q, rd);
    vec3 a = q - b * rd;
    float disc = @{sphere}.w * @{sphere}.w - dot(a, a);
    if (disc >= 0.0) {
        float s = sqrt(disc);
        if (s - b > 0.0) {
            enter = min(enter, -b - s);
            exit = max(exit, s - b);
        }
    }
}

// @part span-grown
// boundsSpan with each sphere of radius r, q from ro, grown by grow * (q + r):
// a soft shadow's penumbra (see soft-span).
vec2 boundsSpanGrown(vec3 ro, vec3 rd, float grow) {
    float enter = uDrawDist;
    float exit = 0.0;
    // @slot spheres
    return vec2(enter, min(exit, uDrawDist));
}

// @part span-grown-loop
for (int i = 0; i < @{count}; i++) {
    vec3 q = ro - @{sphere}.xyz;
    float r = @{sphere}.w + grow * (length(q) + @{sphere}.w);
    float b = dot(q, rd);
    vec3 a = q - b * rd;
    float disc = r * r - dot(a, a);
    if (disc >= 0.0) {
        float s = sqrt(disc);
        if (s - b > 0.0) {
            enter = min(enter, -b - s);
            exit = max(exit, s - b);
        }
    }
}

// @part soft-span
// A plane before the light hides it (`blocked-by-plane`: return 0, or, for a march
// that takes samples first, occlusion-taps.glsl, set seen to 0 and reach to -1 so
// that no shadow turn runs); a span that ends where it starts leaves it lit
// (`empty-span`: return 1; with samples first, the loop's turn 0 stops there).
if (planesHit(o, l) < reach) {
    // @slot blocked-by-plane
}
vec2 span = softness < 0.5 ? boundsSpanGrown(o, l, softness / (1.0 - softness)) : vec2(0.0, uDrawDist);
t = max(span.x, 0.0);
reach = min(reach, span.y);
// @slot empty-span

// @part along
// What the march steps by: as map (mapFinite with bounds), each grid's unlisted
// members bounded along the ray rd too.
float @{name}(vec3 p, vec3 rd) {
    float d = uDrawDist;
    // @slot distance-terms
    return d;
}
