#pragma language glsl3
// A hand-written port of scenes/twisted-tower.fnl: the baseline a person would write in
// Shadertoy style, to compare the generated shader's speed against. Every scene value
// is a constant here; only the camera basis and the target size come in as uniforms
// (the same uniforms the generated shader takes, so the same packing drives both).
//
// The scene, in world coordinates (z up, units of the scene file):
//   - a ground plane at z = 0;
//   - a stone tower: a square terrace slab (7 x 7 x 0.6) joined by a four-step stairs
//     union (radius 0.9) to a hexagonal shaft (apothem 1.3, 8 high, centred at
//     z = 4.6) twisted by 22 degrees per unit of height;
//   - a red core: a 0.9 x 3.2 x 7.6 box at z = 4.6 twisted by -30 degrees per unit;
//   - a golden crown: an octahedron (corners 1.2 out) stretched 2.2 times along z, at
//     z = 9.9;
//   - a bridge: a rounded 6 x 1.2 x 0.3 slab at (6, -1, 1.8), bent by -14 degrees per
//     unit along x into an arc.
// The twist and bend distances are divided by their Lipschitz factors, and every
// object is clipped to (and skipped with) its bounding box.
//
// Shading is the app's modern model: one sun with soft shadows, sky ambient with
// occlusion, Blinn-Phong specular with Schlick's Fresnel, fog, one mirror bounce, an
// exponential tone map and sRGB gamma. Colours are linear (the scene's colours ^ 2.2).
//
// The camera sits at the origin: positions in this shader are camera-relative, and
// map() adds the camera's world position back.

uniform vec2 uResolution;
uniform vec3 uCamForward;
uniform vec3 uCamRight;
uniform vec3 uCamUp;          // points down the screen, as pixel y grows downwards
uniform float uProjDist;      // 1 / tan(fov / 2)

// Camera and march settings.
const vec3 kCamPos = vec3(18.0, -21.0, 8.0);  // camera world position
const float kDrawDist = 300.0;
const int kMaxSteps = 500;
const float kEpsilon = 0.0001;      // hit when a step is below this times the distance
const int kShadowSteps = 128;

// Materials by object id: linear albedo (the scene's colour ^ 2.2) and mirror amount.
// Every roughness is 0.5, and nothing glows.
const vec4 kMaterials[5] = vec4[5](
    vec4(0.172611, 0.217638, 0.148302, 0.0),   // 0 ground (0.45 0.5 0.42)
    vec4(0.612066, 0.578906, 0.515596, 0.0),   // 1 tower stone (0.8 0.78 0.74)
    vec4(0.699394, 0.0993, 0.047366, 0.2),     // 2 core (0.85 0.35 0.25)
    vec4(0.893289, 0.612066, 0.07074, 0.5),    // 3 crown (0.95 0.8 0.3)
    vec4(0.217638, 0.26841, 0.387623, 0.0));   // 4 bridge (0.5 0.55 0.65)

// Lighting.
const vec3 kSunDir = vec3(-0.604551266, -0.45341345, 0.654930538);  // toward the sun
const vec3 kSunColor = vec3(3.0, 2.37933052, 1.59314768);  // (1 0.9 0.75) ^ 2.2 * 3
const float kSunSoftness = 0.03;
const vec2 kSunEdge = vec2(0.999657325, 0.999780683);   // cos 1.5 and cos 1.2 degrees
const vec3 kSkyZenith = vec3(0.0473661427, 0.133208513, 0.531049225);   // (0.25 0.4 0.75) ^ 2.2
const vec3 kSkyHorizon = vec3(0.456263458, 0.531049225, 0.699393572);   // (0.7 0.75 0.85) ^ 2.2
const vec3 kFogColor = kSkyHorizon;
const float kFogDensity = 0.002;
const float kAmbient = 0.45;
const float kAoStrength = 0.7;
const float kAoRadius = 1.0;
const float kExposure = 1.1;
const float kShininess = 64.0;      // exp2(1 + 10 * (1 - roughness 0.5))

float sdBox(vec3 p, vec3 b) {
    vec3 q = abs(p) - b;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float sdRoundBox(vec3 p, vec3 b, float r) {
    return sdBox(p, b) - r;
}

// Hexagonal prism along z: apothem r, half height h.
float sdHexPrism(vec3 p, float r, float h) {
    const vec2 k = vec2(-0.8660254037844386, 0.5);
    float e = r * 0.5773502691896258;  // half a side: r tan 30 degrees
    p = abs(p);
    p.xy -= 2.0 * min(dot(k, p.xy), 0.0) * k;
    vec2 d = vec2(length(p.xy - vec2(clamp(p.x, -e, e), r)) * sign(p.y - r), p.z - h);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}

float sdOctahedron(vec3 p, float s) {
    p = abs(p);
    float m = p.x + p.y + p.z - s;
    vec3 q;
    if (3.0 * p.x < m) q = p.xyz;
    else if (3.0 * p.y < m) q = p.yzx;
    else if (3.0 * p.z < m) q = p.zxy;
    else return m * 0.5773502691896258;
    float k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
    return length(vec3(q.x, q.y - s + k, q.z - k));
}

// A twist's distance correction: a point at radius rho from the axis moves k rho per
// unit of height, so the field is divided by its local Lipschitz factor (taken at no
// less than the child's radius rho0).
float twistScale(vec2 xy, float k, float rho0) {
    float v = abs(k) * max(length(xy), rho0);
    return 0.5 * (v + sqrt(v * v + 4.0));
}

// The finite objects, at world position w: the distance to the nearest one when it is
// nearer than d, else d; id becomes that object's id. Each object is skipped when its
// bounding box is farther than d, and clipped to that box.
float objects(vec3 w, float d, inout int id) {
    // The tower: terrace slab and twisted hex shaft, joined in four stairs.
    float bound = sdBox(w, vec3(4.4, 4.4, 9.5));
    if (bound < d) {
        float slab = sdBox(w - vec3(0.0, 0.0, 0.3), vec3(3.5, 3.5, 0.3));
        vec3 q = w - vec3(0.0, 0.0, 4.6);
        float k = 0.383972435;  // 22 degrees per unit of height
        float c = cos(k * q.z);
        float s = sin(k * q.z);
        vec3 r = vec3(c * q.x + s * q.y, -s * q.x + c * q.y, q.z);
        float shaft = sdHexPrism(r, 1.3, 4.0) / twistScale(q.xy, k, 1.9857828);
        shaft = max(shaft, sdBox(q, vec3(1.9857828, 1.9857828, 4.0)));
        // Stairs union of radius 0.9 in 4 steps.
        float step = 0.9 / 4.0;
        float u = min(slab, shaft);
        for (float i = 0.0; i < 4.0; i += 1.0) {
            u = min(u, max(slab - (i + 1.0) * step, shaft - (4.0 - i) * step));
        }
        u = max(u, bound);
        if (u < d) { d = u; id = 1; }
    }

    // The core: a box twisted by -30 degrees per unit of height.
    vec3 q = w - vec3(0.0, 0.0, 4.6);
    bound = sdBox(q, vec3(1.66207701, 1.66207701, 3.8));
    if (bound < d) {
        float k = -0.523598776;
        float c = cos(k * q.z);
        float s = sin(k * q.z);
        vec3 r = vec3(c * q.x + s * q.y, -s * q.x + c * q.y, q.z);
        float core = sdBox(r, vec3(0.45, 1.6, 3.8)) / twistScale(q.xy, k, 1.66207701);
        core = max(core, bound);
        if (core < d) { d = core; id = 2; }
    }

    // The crown: an octahedron stretched 2.2 times along z (the smallest factor, 1,
    // scales its distance).
    q = w - vec3(0.0, 0.0, 9.9);
    bound = sdBox(q, vec3(1.2, 1.2, 2.64));
    if (bound < d) {
        float crown = max(sdOctahedron(q / vec3(1.0, 1.0, 2.2), 1.2), bound);
        if (crown < d) { d = crown; id = 3; }
    }

    // The bridge: a rounded slab bent by -14 degrees per unit along x.
    q = w - vec3(6.0, -1.0, 1.8);
    bound = sdBox(q, vec3(3.00374766, 0.6, 3.00374766));
    if (bound < d) {
        float k = -0.244346095;
        float c = cos(k * q.x);
        float s = sin(k * q.x);
        vec3 r = vec3(c * q.x - s * q.z, q.y, s * q.x + c * q.z);
        float bridge = sdRoundBox(r, vec3(2.9, 0.5, 0.05), 0.1)
                       / (1.0 + abs(k) * max(length(q.xz), 3.00374766));
        bridge = max(bridge, bound);
        if (bridge < d) { d = bridge; id = 4; }
    }
    return d;
}

// The scene's distance at camera-relative p: the ground (z = 0) and the objects, never
// more than the draw distance.
float map(vec3 p) {
    vec3 w = p + kCamPos;
    int id = 0;
    return objects(w, min(kDrawDist, w.z), id);
}

// The material of the nearest surface at p (once per hit).
vec4 material(vec3 p) {
    vec3 w = p + kCamPos;
    int id = 0;
    objects(w, min(kDrawDist, w.z), id);
    return kMaterials[id];
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
        int id = 0;
        float d = objects(ro + rd * t + kCamPos, kDrawDist, id);
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

// Fog colour along rd: the horizon colour, tinted toward the sun's hue near it.
vec3 fogColor(vec3 rd) {
    vec3 sunHue = kSunColor / 3.0 * 0.699393572;  // brightest channel 1, times the fog's
    return mix(kFogColor, sunHue, pow(max(dot(rd, kSunDir), 0.0), 8.0));
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
    // The camera ray and one mirror bounce.
    for (int bounce = 0; bounce <= 1; bounce++) {
        float t = march(ro, rd);
        if (t >= kDrawDist) {
            col += weight * sky(rd);
            break;
        }
        vec3 p = ro + rd * t;
        vec4 m = material(p);  // first: p is exactly on the surface
        vec3 albedo = m.rgb;
        float mirror = m.w;
        vec3 n = calcNormal(p);
        // Share of light reflected: Fresnel from the mirror amount, times
        // smoothness^2 = 0.25 for roughness 0.5.
        float f0 = mix(0.04, 1.0, mirror);
        float reflected = (f0 + (1.0 - f0) * pow(1.0 - clamp(dot(n, -rd), 0.0, 1.0), 5.0)) * 0.25;
        vec3 skyLight = mix(kSkyHorizon, kSkyZenith, 0.5 + 0.5 * n.z);
        vec3 surface = (1.0 - reflected) * (sunLight(p, n, -rd, albedo, mirror)
                                            + albedo * skyLight * (kAmbient * occlusion(p, n)));
        float through = exp(-kFogDensity * t);
        col += weight * ((1.0 - through) * fogColor(rd));
        weight *= through;
        col += weight * surface;
        weight *= reflected * mix(vec3(1.0), albedo, mirror);
        ro = p + n * (2.0 * normalDelta(p));
        rd = reflect(rd, n);
    }
    return vec4(pow(1.0 - exp(-col * kExposure), vec3(1.0 / 2.2)), 1.0);
}
