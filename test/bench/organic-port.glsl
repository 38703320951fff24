#pragma language glsl3
// A hand-written port of scenes/organic.fnl (its parameters at their values in the
// file): the baseline a person would write in Shadertoy style, to compare the generated
// shader's compile and frame times against (issue 42). Every scene value is a
// constant here; only the camera basis and the target size come in as uniforms (the
// same uniforms the generated shader takes, so the same packing drives both).
//
// The scene, in world coordinates (z up, units of the scene file):
//   - a ground plane at z = 0;
//   - a creature: an ellipsoid body, a head (a sphere and a capsule neck melted with an
//     exponential smooth union), four round-cone legs, a thin capsule tail and a vesica
//     beak, all melted with polynomial smooth unions of radius 0.35; two eyes cut with
//     smooth subtractions of radius 0.08. Its colour blends as its distances do: the
//     skin, the tail's and the beak's colours mixed by each union's weight, the eyes'
//     dark colour by each subtraction's;
//   - a rock: an ellipsoid displaced by a sine wave (amplitude 0.06, frequency 9), its
//     distance divided by its Lipschitz factor;
//   - a lens: the smooth intersection (radius 0.1) of two unit spheres 1.4 apart.
// Each object is clipped to (and skipped with) its bounding box, as the app's far
// field does.
//
// Shading is the app's modern model: one sun with soft shadows, sky ambient with
// occlusion, Blinn-Phong specular with Schlick's Fresnel, one mirror bounce, an
// exponential tone map and sRGB gamma. Colours blend in the scene's (sRGB) values and
// are made linear (^ 2.2) once per hit, as the app does.
//
// The camera sits at the origin: positions in this shader are camera-relative, and
// map() adds the camera's world position back.

uniform vec2 uResolution;
uniform vec3 uCamForward;
uniform vec3 uCamRight;
uniform vec3 uCamUp;          // points down the screen, as pixel y grows downwards
uniform float uProjDist;      // 1 / tan(fov / 2)

// Camera and march settings.
const vec3 kCamPos = vec3(5.5, -6.0, 3.2);  // camera world position
const float kDrawDist = 200.0;
const int kMaxSteps = 500;
const float kEpsilon = 0.0001;      // hit when a step is below this times the distance
const int kShadowSteps = 128;

// Colours (the scene's, sRGB) and mirror amounts; every roughness is 0.5.
const vec3 kGround = vec3(0.85, 0.8, 0.68);
const vec3 kSkin = vec3(0.85, 0.45, 0.35);
const vec3 kTail = vec3(0.95, 0.7, 0.3);
const vec3 kBeak = vec3(0.95, 0.8, 0.2);
const vec3 kEye = vec3(0.05, 0.05, 0.08);
const vec3 kRock = vec3(0.45, 0.47, 0.5);
const vec3 kLens = vec3(0.6, 0.8, 0.95);
const float kSkinMirror = 0.15;

// Lighting.
const vec3 kSunDir = vec3(0.374817029, -0.499756038, 0.780868809);  // toward the sun
const vec3 kSunColor = vec3(3.0, 2.67986666, 2.09818072);  // (1 0.95 0.85) ^ 2.2 * 3
const float kSunSoftness = 0.05;
const vec2 kSunEdge = vec2(0.999657325, 0.999780683);   // cos 1.5 and cos 1.2 degrees
const vec3 kSkyZenith = vec3(0.0707402777, 0.217637641, 0.699393572);   // (0.3 0.5 0.85) ^ 2.2
const vec3 kSkyHorizon = vec3(0.531049225, 0.646234999, 0.832402202);   // (0.75 0.82 0.92) ^ 2.2
const float kAmbient = 0.5;
const float kAoStrength = 0.9;
const float kAoRadius = 0.4;
const float kExposure = 1.1;
const float kShininess = 64.0;      // exp2(1 + 10 * (1 - roughness 0.5))

float sdBox(vec3 p, vec3 b) {
    vec3 q = abs(p) - b;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float sdSphere(vec3 p, float r) {
    return length(p) - r;
}

float sdCapsule(vec3 p, vec3 a, vec3 b, float r) {
    vec3 pa = p - a;
    vec3 ba = b - a;
    float h = clamp(dot(pa, ba) / dot(ba, ba), 0.0, 1.0);
    return length(pa - ba * h) - r;
}

// Ellipsoid of radii r (smallest m): inside, a bound; outside, the distance to the
// nearest point, found by three Newton steps on its Lagrange parameter.
float sdEllipsoid(vec3 p, vec3 r, float m) {
    float k0 = length(p / r);
    float k1 = length(p / (r * r));
    if (k0 < 1.0) {
        return max(k1 > 0.0 ? k0 * (k0 - 1.0) / k1 : -m, m * (k0 - 1.0));
    }
    vec3 r2 = r * r;
    float t = (k0 - 1.0) * k0 * k0 / (k1 * k1);
    for (int i = 0; i < 3; i++) {
        vec3 w = 1.0 / (t + r2);
        vec3 q = r * p * w;
        float s = dot(q, q);
        t += (sqrt(s) - 1.0) * s / dot(q * q, w);
    }
    vec3 x = r2 * p / (t + r2);
    x /= length(x / r);
    vec3 g = x / r2;
    return dot(p - x, g) / length(g);
}

// Round cone along z, centred: a sphere of radius r1 at z = -h joined to one of
// radius r2 at z = h; (c, s): the cosine and sine of its side's slope.
float sdRoundCone(vec3 p, float c, float s, float h, float r1, float r2) {
    float q = length(p.xy);
    float k = -q * s + p.z * c;
    if (k < -c * h) return length(vec2(q, p.z + h)) - r1;
    if (k > c * h) return length(vec2(q, p.z - h)) - r2;
    return q * c + p.z * s + s * h - r1;
}

// Vesica (a lens of two arcs) turned about z: radius r of the arcs, b their centres'
// distance from the axis, h half its length.
float sdVesica(vec3 p, float r, float b, float h) {
    float q = length(p.xy);
    float z = abs(p.z);
    if ((z - h) * b > q * h) return length(vec2(q, z - h));
    return length(vec2(q + b, z)) - r;
}

// Polynomial smooth union; w: the weight of a's colour.
float smoothUnion(float a, float b, float r, out float w) {
    w = clamp(0.5 + 0.5 * (b - a) / r, 0.0, 1.0);
    return mix(b, a, w) - r * w * (1.0 - w);
}

// Exponential smooth union.
float smoothUnionExp(float a, float b, float r) {
    float m = min(a, b);
    return m - r * log(exp((m - a) / r) + exp((m - b) / r));
}

// Polynomial smooth subtraction of b from a; w: the weight of a's colour.
float smoothSubtraction(float a, float b, float r, out float w) {
    float h = clamp(0.5 - 0.5 * (a + b) / r, 0.0, 1.0);
    w = 1.0 - h;
    return mix(a, -b, h) + r * h * (1.0 - h);
}

float smoothIntersection(float a, float b, float r) {
    float h = clamp(0.5 - 0.5 * (b - a) / r, 0.0, 1.0);
    return mix(b, a, h) + r * h * (1.0 - h);
}

// The creature at world position w: its distance, and its colour in col.
float creature(vec3 w, out vec3 col) {
    float body = sdEllipsoid(w - vec3(0.0, 0.0, 1.5), vec3(1.3, 0.8, 0.7), 0.7);
    float head = smoothUnionExp(sdSphere(w - vec3(1.55, 0.0, 2.25), 0.55),
                                sdCapsule(w, vec3(0.9, 0.0, 1.8), vec3(1.4, 0.0, 2.15), 0.3), 0.25);
    float legs = kDrawDist;
    for (int i = 0; i < 4; i++) {
        vec3 at = vec3(i < 2 ? -0.7 : 0.7, i % 2 == 0 ? -0.5 : 0.5, 0.68);
        legs = min(legs, sdRoundCone(w - at, 0.994987437, -0.1, 0.5, 0.18, 0.28));
    }
    float tail = sdCapsule(w, vec3(-1.2, 0.0, 1.6), vec3(-2.0, 0.0, 2.3), 0.12);
    vec3 b = w - vec3(2.15, 0.0, 2.2);
    float beak = sdVesica(vec3(-b.z, b.y, b.x), 0.464090909, 0.354090909, 0.3);
    float k;
    float d = smoothUnion(body, head, 0.35, k);
    d = smoothUnion(d, legs, 0.35, k);
    d = smoothUnion(d, tail, 0.35, k);
    col = mix(kTail, kSkin, k);
    d = smoothUnion(d, beak, 0.35, k);
    col = mix(kBeak, col, k);
    d = smoothSubtraction(d, sdSphere(w - vec3(1.92, -0.3, 2.42), 0.12), 0.08, k);
    col = mix(kEye, col, k);
    d = smoothSubtraction(d, sdSphere(w - vec3(1.92, 0.3, 2.42), 0.12), 0.08, k);
    col = mix(kEye, col, k);
    return d;
}

// The objects at world position w: the distance to the nearest one when it is nearer
// than d, else d; col and mirror become that object's. Each object is skipped when
// its bounding box is farther than d, and clipped to that box.
float objects(vec3 w, float d, inout vec3 col, inout float mirror) {
    float bound = sdBox(w - vec3(0.165, 0.0, 0.175), vec3(2.635, 1.15, 3.225));
    if (bound < d) {
        vec3 c;
        float u = max(creature(w, c), bound);
        if (u < d) { d = u; col = c; mirror = kSkinMirror; }
    }

    vec3 q = w - vec3(-2.2, -2.0, 0.3);
    bound = sdBox(q, vec3(0.96, 0.76, 0.61));
    if (bound < d) {
        float rock = sdEllipsoid(q, vec3(0.9, 0.7, 0.55), 0.55)
                     + 0.06 * sin(9.0 * q.x) * sin(9.0 * q.y) * sin(9.0 * q.z);
        rock = max(rock * 0.516713769, bound);  // 1 / its Lipschitz factor 1.93531
        if (rock < d) { d = rock; col = kRock; mirror = 0.0; }
    }

    q = w - vec3(0.5, -2.4, 0.6);
    bound = sdBox(q, vec3(1.0, 1.0, 1.7));
    if (bound < d) {
        float lens = max(smoothIntersection(sdSphere(q + vec3(0.0, 0.0, 0.7), 1.0),
                                            sdSphere(q - vec3(0.0, 0.0, 0.7), 1.0), 0.1), bound);
        if (lens < d) { d = lens; col = kLens; mirror = 0.0; }
    }
    return d;
}

// The scene's distance at camera-relative p: the ground (z = 0) and the objects, never
// more than the draw distance.
float map(vec3 p) {
    vec3 w = p + kCamPos;
    vec3 col;
    float mirror;
    return objects(w, min(kDrawDist, w.z), col, mirror);
}

// The colour (sRGB) and mirror amount of the nearest surface at p (once per hit).
vec4 material(vec3 p) {
    vec3 w = p + kCamPos;
    vec3 col = kGround;
    float mirror = 0.0;
    objects(w, min(kDrawDist, w.z), col, mirror);
    return vec4(col, mirror);
}

// Sphere tracing from ro along rd: the distance to the first hit, or kDrawDist for
// none. The ground is met in closed form; the march looks for objects before it.
// The hit test is relative to the distance from the camera.
float march(vec3 ro, vec3 rd) {
    float tGround = rd.z < 0.0 ? -(ro.z + kCamPos.z) / rd.z : kDrawDist;
    float tMax = min(tGround, kDrawDist);
    float t0 = length(ro);
    float t = 0.0;
    for (int i = 0; i < kMaxSteps; i++) {
        vec3 col;
        float mirror;
        float d = objects(ro + rd * t + kCamPos, kDrawDist, col, mirror);
        if (d < kEpsilon * (t0 + t)) return t + d;
        t += d;
        if (t >= tMax) break;
    }
    return tMax;
}

// Finite-difference step for normals, and the offset of secondary rays (twice this).
float normalDelta(vec3 p) {
    float dist = length(p);
    return max(kEpsilon * dist, 0.000001 * (1.0 + dist));
}

// Tetrahedron normal: four samples at the corners of a tetrahedron.
vec3 calcNormal(vec3 p) {
    float h = normalDelta(p);
    const vec2 k = vec2(1.0, -1.0);
    return normalize(k.xyy * map(p + k.xyy * h) + k.yyx * map(p + k.yyx * h)
                     + k.yxy * map(p + k.yxy * h) + k.xxx * map(p + k.xxx * h));
}

// Sky: horizon to zenith, darker below the horizon, and the sun's disc.
vec3 sky(vec3 rd) {
    vec3 c = mix(kSkyHorizon, kSkyZenith, sqrt(clamp(rd.z, 0.0, 1.0)));
    c *= 1.0 - 0.5 * clamp(-4.0 * rd.z, 0.0, 1.0);
    return c + kSunColor * (8.0 * smoothstep(kSunEdge.x, kSunEdge.y, dot(rd, kSunDir)));
}

// Ambient occlusion: five samples along the normal out to kAoRadius.
float occlusion(vec3 p, vec3 n) {
    float occ = 0.0;
    float weight = 1.0;
    for (int i = 1; i <= 5; i++) {
        float h = kAoRadius * float(i) / 5.0;
        occ += weight * clamp((h - map(p + n * h)) / h, 0.0, 1.0);
        weight *= 0.5;
    }
    return clamp(1.0 - kAoStrength * occ / 1.9375, 0.0, 1.0);  // 1.9375: sum of weights
}

// Soft shadow toward the sun (Quilez's improved penumbra estimate).
float softShadow(vec3 o, vec3 l) {
    float t0 = length(o);
    float seen = 1.0;
    float t = 0.0;
    float hPrev = 10000000000.0;
    for (int i = 0; i < kShadowSteps; i++) {
        float h = map(o + l * t);
        if (h < kEpsilon * (t0 + t)) return 0.0;
        float y = h * h / (2.0 * hPrev);
        float closest = sqrt(max(h * h - y * y, 0.0));
        seen = min(seen, closest / (kSunSoftness * max(t - y, 0.000001)));
        hPrev = h;
        t += h;
        if (t >= kDrawDist) break;
    }
    seen = clamp(seen, 0.0, 1.0);
    return seen * seen * (3.0 - 2.0 * seen);
}

// The sun's light at p: Lambert plus energy-normalised Blinn-Phong with Fresnel.
vec3 sunLight(vec3 p, vec3 n, vec3 v, vec3 albedo, float mirror) {
    float lambert = dot(n, kSunDir);
    if (lambert <= 0.0) return vec3(0.0);
    vec3 radiance = kSunColor * (lambert * softShadow(p + n * (2.0 * normalDelta(p)), kSunDir));
    vec3 h = normalize(kSunDir + v);
    float f0 = mix(0.04, 1.0, mirror);
    float fresnel = f0 + (1.0 - f0) * pow(1.0 - clamp(dot(kSunDir, h), 0.0, 1.0), 5.0);
    vec3 specular = mix(vec3(1.0), albedo, mirror)
                    * (fresnel * (kShininess + 8.0) / 8.0 * pow(clamp(dot(n, h), 0.0, 1.0), kShininess));
    return radiance * (albedo + specular);
}

vec4 effect(vec4 vertexColor, Image tex, vec2 texCoord, vec2 px) {
    vec2 uv = vec2((px.x / uResolution.x - 0.5) * (uResolution.x / uResolution.y),
                   px.y / uResolution.y - 0.5);
    vec3 ro = vec3(0.0);
    vec3 rd = normalize(uCamForward * uProjDist + uCamRight * uv.x + uCamUp * uv.y);
    vec3 col = vec3(0.0);
    vec3 weight = vec3(1.0);
    for (int bounce = 0; bounce <= 1; bounce++) {
        float t = march(ro, rd);
        if (t >= kDrawDist) {
            col += weight * sky(rd);
            break;
        }
        vec3 p = ro + rd * t;
        vec4 m = material(p);  // first: p is exactly on the surface
        vec3 albedo = pow(m.rgb, vec3(2.2));
        float mirror = m.w;
        vec3 n = calcNormal(p);
        float f0 = mix(0.04, 1.0, mirror);
        float reflected = (f0 + (1.0 - f0) * pow(1.0 - clamp(dot(n, -rd), 0.0, 1.0), 5.0)) * 0.25;
        vec3 skyLight = mix(kSkyHorizon, kSkyZenith, 0.5 + 0.5 * n.z);
        vec3 surface = (1.0 - reflected) * (sunLight(p, n, -rd, albedo, mirror)
                                            + albedo * skyLight * (kAmbient * occlusion(p, n)));
        col += weight * surface;
        weight *= reflected * mix(vec3(1.0), albedo, mirror);
        ro = p + n * (2.0 * normalDelta(p));
        rd = reflect(rd, n);
    }
    return vec4(pow(1.0 - exp(-col * kExposure), vec3(1.0 / 2.2)), 1.0);
}
