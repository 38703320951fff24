// The tape interpreter (src/sdf/interpret.fnl, src/sdf/strategies/interpreted.fnl):
// one shader for every tape of its instruction set. The tape's rows (uTape) and the
// program (uProgram) are rgba32f images, a line @{width} texels wide; the program's
// layout is at the top of interpret.fnl. The slot cases holds one case of the switch
// per function of the set (the functions themselves are written before this); the
// tape's own instructions (far field, Lipschitz division, material, the end of a
// repetition) are the first opcodes. Registers: @{registers} of each kind, so any
// program of the set runs on it.
uniform sampler2D uTape;  // the tape's rows, then the instance bank's, a texel each
uniform sampler2D uProgram;  // the interpreter's program
// The tape interpreter: @{functions} functions.
const int kTapeWidth = @{width};
const @{material-type} kTapeNoMaterial = @{material-zero};
float gTapeD[@{registers}];
vec3 gTapeP[@{registers}];
@{material-type} gTapeM[@{registers}];
vec3 gTapeGradient;

vec4 tapeCode(int i) {
    return texelFetch(uProgram, ivec2(i % kTapeWidth, i / kTapeWidth), 0);
}

// Argument k of the instruction at pc: an index of a float in the tape's rows (the
// second of the pair where the field is read as an estimate).
int tapeArg(int pc, int k) {
    vec4 t = tapeCode(pc + 2 + k / 2);
    vec2 a = (k % 2 == 0) ? t.xy : t.zw;
    return int(gEstimate ? a.y : a.x);
}

vec4 tapeRowAt(int i) {
    int row = i / 4;
    return texelFetch(uTape, ivec2(row % kTapeWidth, row / kTapeWidth), 0);
}

float tapeFloat(int pc, int k) { int i = tapeArg(pc, k); return tapeRowAt(i)[i % 4]; }
vec2 tapeVec2(int pc, int k) {
    int i = tapeArg(pc, k);
    vec4 r = tapeRowAt(i);
    int o = i % 4;
    return vec2(r[o], r[o + 1]);
}
vec3 tapeVec3(int pc, int k) {
    int i = tapeArg(pc, k);
    vec4 r = tapeRowAt(i);
    return i % 4 == 0 ? r.xyz : r.yzw;
}
vec4 tapeVec4(int pc, int k) { return tapeRowAt(tapeArg(pc, k)); }

// Runs the code from pc to end on the registers. At guardPc (an object's guard: its
// box's distance in register box), stops when the box is no nearer than dmin: returns
// false then (the object cannot lower dmin).
bool tapeRun(int pc, int end, int guardPc, int box, float dmin, bool materials) {
    int loopStart[@{depth}];
    int loopCell[@{depth}];
    int depth = 0;
    while (pc < end) {
        if (pc == guardPc && gTapeD[box] >= dmin) return false;
        vec4 head = tapeCode(pc);
        vec4 t = tapeCode(pc + 1);
        int op = int(head.x);
        int r0 = int(head.y), r1 = int(head.z), r2 = int(head.w);
        switch (op) {
        case @{far}: gTapeD[r0] = max(gTapeD[r1], gTapeD[r2]); break;
        case @{divide}: gTapeD[r0] = gTapeD[r1] * t.x; break;
        case @{material}: {
            if (materials) {
                int row = int(tapeCode(pc + 2).x);
                // @slot material-read
            }
            break;
        }
        case @{cells-end}: {
            // r0: the body's distance, r1: the repetition's; t.x, t.y: materials.
            // With t.z 1, a neighbour's box (r0) at its cell's point (t.x), but
            // where that is the own cell's point (t.y).
            if (t.z > 0.5) {
                gTapeD[r1] = min(gTapeD[r1], gTapeP[int(t.x)] == gTapeP[int(t.y)] ? 10000000000.0 : gTapeD[r0]);
            } else if (materials) {
                if (gTapeD[r0] < gTapeD[r1]) {
                    gTapeD[r1] = gTapeD[r0];
                    gTapeM[int(t.y)] = gTapeM[int(t.x)];
                }
            } else {
                gTapeD[r1] = min(gTapeD[r1], gTapeD[r0]);
            }
            int cell = loopCell[depth - 1] + 1;
            if (cell < int(tapeCode(r2 + 1).z)) {
                loopCell[depth - 1] = cell;
                pc = r2;
                continue;
            }
            depth--;
            break;
        }
        // @slot cases
        }
        pc += int(t.w);
    }
    return !(guardPc == end && gTapeD[box] >= dmin);
}

// Whether object k is a half-space, met in closed form by a bounded march.
bool tapeHalfSpace(int k) { return tapeCode(3 + 3 * k).x > 0.5; }

// d lowered by the program's objects at p: only object `only` (all when -1), none of
// them object `skip`; with `finite`, none of the half-spaces (a bounded march's
// mapFinite).
float tapeMin(vec3 p, float d, int only, int skip, bool finite) {
    int count = int(tapeCode(0).x);
    for (int k = 0; k < count; k++) {
        if (k == skip || (only >= 0 && k != only) || (finite && tapeHalfSpace(k))) continue;
        vec4 span = tapeCode(1 + 3 * k);
        vec4 regs = tapeCode(2 + 3 * k);
        gTapeP[0] = p;
        if (tapeRun(int(span.x), int(span.y), int(span.z), int(regs.z), d, false)) {
            d = min(d, gTapeD[int(regs.x)]);
        }
    }
    return d;
}

// The nearest object below d at p (its number in object, -1 when none is) and its
// material.
float tapeColor(vec3 p, float d, out @{material-type} material, out int object) {
    int count = int(tapeCode(0).x);
    object = -1;
    material = kTapeNoMaterial;
    for (int k = 0; k < count; k++) {
        vec4 span = tapeCode(1 + 3 * k);
        vec4 regs = tapeCode(2 + 3 * k);
        gTapeP[0] = p;
        if (tapeRun(int(span.x), int(span.y), int(span.z), int(regs.z), d, true)) {
            float dk = gTapeD[int(regs.x)];
            if (dk < d) {
                d = dk;
                object = k;
                material = gTapeM[int(regs.y)];
            }
        }
    }
    return d;
}

// Whether object k has its exact gradient in closed form; that gradient at p.
bool tapeExact(int k) { return tapeCode(1 + 3 * k).w >= 0.0; }
vec3 tapeGradient(vec3 p, int k) {
    vec4 span = tapeCode(1 + 3 * k);
    vec4 regs = tapeCode(2 + 3 * k);
    gTapeP[0] = p;
    gTapeGradient = vec3(0.0, 0.0, 1.0);
    tapeRun(int(span.w), int(regs.w), -1, 0, 0.0, false);
    return gTapeGradient;
}

// planesHit's t lowered by the program's half-spaces along the ray ro + t rd: a
// half-space's distance s at ro over the ray's rate v along its normal (its
// gradient); 0 from inside it, -s / v ahead (emit-glsl.fnl's plane-block).
float tapePlanesHit(vec3 ro, vec3 rd, float t) {
    int count = int(tapeCode(0).x);
    for (int k = 0; k < count; k++) {
        if (!tapeHalfSpace(k)) continue;
        vec4 span = tapeCode(1 + 3 * k);
        vec4 regs = tapeCode(2 + 3 * k);
        gTapeP[0] = ro;
        tapeRun(int(span.x), int(span.y), -1, 0, 0.0, false);
        float s = gTapeD[int(regs.x)];
        float v = dot(rd, tapeGradient(ro, k));
        if (s <= 0.0) {
            t = 0.0;
        } else if (v < 0.0) {
            t = min(t, -s / v);
        }
    }
    return t;
}
