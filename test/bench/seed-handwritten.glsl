#pragma language glsl3
// Hand-written raymarcher for scenes/seed.fnl, the benchmark's baseline: the same
// algorithm as the generated shader (article's march, one-sided normals, hard shadows,
// three mirror bounces, the same guards against zero vectors and float32 resolution),
// written out by hand for this one scene. It takes the same uniforms, so the same
// uniform packing drives both.

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
uniform vec4 uSphere[2];
uniform vec3 uSphereColor[2];
uniform vec3 uBoxCenter[3];
uniform vec3 uBoxHalfSize[3];
uniform vec3 uBoxColor[3];
uniform float uPlaneHeight[1];
uniform vec3 uPlaneColor[1];

float box(vec3 p, vec3 c, vec3 h) {
    vec3 q = abs(p - c) - h;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float scene(vec3 p) {
    float d = uDrawDist;
    d = min(d, length(p - uSphere[0].xyz) - uSphere[0].w);
    d = min(d, length(p - uSphere[1].xyz) - uSphere[1].w);
    d = min(d, box(p, uBoxCenter[0], uBoxHalfSize[0]));
    d = min(d, box(p, uBoxCenter[1], uBoxHalfSize[1]));
    d = min(d, box(p, uBoxCenter[2], uBoxHalfSize[2]));
    d = min(d, p.z - uPlaneHeight[0]);
    return d;
}

vec3 colorAt(vec3 p) {
    float d = uDrawDist;
    vec3 c = vec3(0.0);
    float di;
    di = length(p - uSphere[0].xyz) - uSphere[0].w; if (di < d) { d = di; c = uSphereColor[0]; }
    di = length(p - uSphere[1].xyz) - uSphere[1].w; if (di < d) { d = di; c = uSphereColor[1]; }
    di = box(p, uBoxCenter[0], uBoxHalfSize[0]); if (di < d) { d = di; c = uBoxColor[0]; }
    di = box(p, uBoxCenter[1], uBoxHalfSize[1]); if (di < d) { d = di; c = uBoxColor[1]; }
    di = box(p, uBoxCenter[2], uBoxHalfSize[2]); if (di < d) { d = di; c = uBoxColor[2]; }
    di = p.z - uPlaneHeight[0]; if (di < d) { d = di; c = uPlaneColor[0]; }
    return c;
}

float march(vec3 ro, vec3 rd) {
    float t = 0.0;
    for (int i = 0; i < uMaxSteps; i++) {
        float d = scene(ro + rd * t);
        t += d;
        if (d < uEpsilon || t >= uDrawDist) break;
    }
    return t;
}

// Normal step and ray offset: epsilon, but never below what float32 resolves at p.
float delta(vec3 p) {
    return max(uEpsilon, 0.000001 * (1.0 + length(p)));
}

vec3 normalAt(vec3 p) {
    float d = scene(p);
    float h = delta(p);
    vec3 g = vec3(d - scene(p - vec3(h, 0.0, 0.0)),
                  d - scene(p - vec3(0.0, h, 0.0)),
                  d - scene(p - vec3(0.0, 0.0, h)));
    float len = length(g);
    return len > 0.0 ? g / len : vec3(0.0, 0.0, 1.0);
}

float light(vec3 p, vec3 n) {
    vec3 toLight = uLightPos - p;
    float dist = length(toLight);
    vec3 l = dist > 0.0 ? toLight / dist : n;
    float k = clamp(dot(l, n), 0.0, 1.0);
    if (k > 0.0 && march(p + n * (2.0 * delta(p)), l) < uDrawDist) k *= 0.5;
    return k;
}

vec4 effect(vec4 vertexColor, Image tex, vec2 texCoord, vec2 px) {
    vec2 uv = vec2((px.x / uResolution.x - 0.5) * (uResolution.x / uResolution.y),
                   px.y / uResolution.y - 0.5);
    vec3 rd = normalize(uCamForward * uProjDist + uCamRight * uv.x + uCamUp * uv.y);
    float t = march(vec3(0.0), rd);
    if (t >= uDrawDist) return vec4(uEnvColor, 1.0);
    vec3 p = rd * t;
    vec3 n = normalAt(p);
    vec3 col = colorAt(p) * light(p, n);
    for (int b = 1; b <= uReflections; b++) {
        rd = rd - 2.0 * dot(rd, n) * n;
        vec3 o = p + n * (2.0 * delta(p));
        float tr = march(o, rd);
        if (tr >= uDrawDist) {
            col = (col + uEnvColor / float(b)) * 0.5;
            break;
        }
        p = o + rd * tr;
        n = normalAt(p);
        col = (col + colorAt(p) * light(p, n) * 0.5) * 0.66;
    }
    return vec4(col, 1.0);
}
