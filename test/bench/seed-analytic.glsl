#pragma language glsl3
// An analytic ray tracer of scenes/seed.fnl: the floor for the marcher's speed (issue
// 11). The same scene and the same shading as the article's (Lambert toward the point
// light, a shadow ray that halves the light when it meets anything, three mirror
// bounces blended as the article blends them), but every ray meets the objects in
// closed form: ray-sphere, the slab test for boxes, ray-plane. Normals are exact. It
// takes the marcher's uniforms, so the same packing drives both; each is read a handful
// of times per ray, not per step, so it reads them directly.

uniform vec2 uResolution;
uniform vec3 uCamForward;
uniform vec3 uCamRight;
uniform vec3 uCamUp;
uniform float uProjDist;
uniform vec3 uLightPos;
uniform vec3 uEnvColor;
uniform int uMaxSteps;
uniform float uEpsilon;
uniform float uDrawDist;
uniform int uReflections;
// The seed's objects as the marcher's tape holds them (src/sdf/lower.fnl), rows in
// file order: each box its centre, its half size, its material; each sphere its centre
// and radius, its material; the plane an unused row, its normal and height, its
// material. Positions are camera-relative, as the marcher's.
uniform vec4 uTape[16];

// Nearest hit along ro + t rd for t in (0, tMax): distance, normal and colour.
struct Hit { float t; vec3 n; vec3 color; };

void sphereHit(vec3 ro, vec3 rd, vec4 s, vec3 color, inout Hit h) {
    vec3 oc = ro - s.xyz;
    float b = dot(oc, rd);
    float c = dot(oc, oc) - s.w * s.w;
    float disc = b * b - c;
    if (disc < 0.0) return;
    float root = sqrt(disc);
    float t = -b - root;
    if (t <= 0.0) t = -b + root;
    if (t > 0.0 && t < h.t) { h.t = t; h.n = (oc + rd * t) / s.w; h.color = color; }
}

void boxHit(vec3 ro, vec3 rd, vec3 c, vec3 halfSize, vec3 color, inout Hit h) {
    vec3 inv = 1.0 / rd;
    vec3 t1 = (c - halfSize - ro) * inv;
    vec3 t2 = (c + halfSize - ro) * inv;
    vec3 lo = min(t1, t2);
    vec3 hi = max(t1, t2);
    float tNear = max(lo.x, max(lo.y, lo.z));
    float tFar = min(hi.x, min(hi.y, hi.z));
    if (tFar < max(tNear, 0.0)) return;
    float t = tNear > 0.0 ? tNear : tFar;
    if (t < h.t) {
        vec3 q = (ro + rd * t - c) / halfSize;
        vec3 a = abs(q);
        vec3 n = a.x > a.y && a.x > a.z ? vec3(sign(q.x), 0.0, 0.0)
               : a.y > a.z ? vec3(0.0, sign(q.y), 0.0) : vec3(0.0, 0.0, sign(q.z));
        h.t = t; h.n = n; h.color = color;
    }
}

void planeHit(vec3 ro, vec3 rd, float height, vec3 color, inout Hit h) {
    if (rd.z == 0.0) return;
    float t = (height - ro.z) / rd.z;
    if (t > 0.0 && t < h.t) { h.t = t; h.n = vec3(0.0, 0.0, ro.z > height ? 1.0 : -1.0); h.color = color; }
}

Hit trace(vec3 ro, vec3 rd) {
    Hit h = Hit(uDrawDist, vec3(0.0, 0.0, 1.0), vec3(0.0));
    sphereHit(ro, rd, uTape[9], uTape[10].rgb, h);
    sphereHit(ro, rd, uTape[11], uTape[12].rgb, h);
    boxHit(ro, rd, uTape[0].xyz, uTape[1].xyz, uTape[2].rgb, h);
    boxHit(ro, rd, uTape[3].xyz, uTape[4].xyz, uTape[5].rgb, h);
    boxHit(ro, rd, uTape[6].xyz, uTape[7].xyz, uTape[8].rgb, h);
    planeHit(ro, rd, uTape[14].w, uTape[15].rgb, h);
    return h;
}

// The marcher's offset off a surface: epsilon, never below what float32 resolves.
float delta(vec3 p) {
    return max(uEpsilon, 0.000001 * (1.0 + length(p)));
}

float light(vec3 p, vec3 n) {
    vec3 toLight = uLightPos - p;
    float dist = length(toLight);
    vec3 l = dist > 0.0 ? toLight / dist : n;
    float k = clamp(dot(l, n), 0.0, 1.0);
    // As the article's shadow ray: anything along it, up to the draw distance.
    if (k > 0.0 && trace(p + n * (2.0 * delta(p)), l).t < uDrawDist) k *= 0.5;
    return k;
}

vec4 effect(vec4 vertexColor, Image tex, vec2 texCoord, vec2 px) {
    vec2 uv = vec2((px.x / uResolution.x - 0.5) * (uResolution.x / uResolution.y),
                   px.y / uResolution.y - 0.5);
    vec3 rd = normalize(uCamForward * uProjDist + uCamRight * uv.x + uCamUp * uv.y);
    Hit h = trace(vec3(0.0), rd);
    if (h.t >= uDrawDist) return vec4(uEnvColor, 1.0);
    vec3 p = rd * h.t;
    vec3 n = h.n;
    vec3 col = h.color * light(p, n);
    for (int b = 1; b <= uReflections; b++) {
        rd = rd - 2.0 * dot(rd, n) * n;
        vec3 o = p + n * (2.0 * delta(p));
        Hit r = trace(o, rd);
        if (r.t >= uDrawDist) {
            col = (col + uEnvColor / float(b)) * 0.5;
            break;
        }
        p = o + rd * r.t;
        n = r.n;
        col = (col + r.color * light(p, n) * 0.5) * 0.66;
    }
    return vec4(col, 1.0);
}
