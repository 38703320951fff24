// Marched field members (src/render/field.fnl's marched-entry is this on the CPU):
// any primitive placed by :pos and :rotate. Its record holds its bounding sphere and
// its kind's number negated; its texels of uFieldObjects (kFieldObjectTexels of them)
// from the fourth on, its rotation into its frame (a unit quaternion) and its packed
// numbers (u, and v when some kind has more than four: kFieldArgTexels).

// The distance of marched kind `kind` at l (in its frame), its numbers u and v.
float fieldKindDistance(int kind, vec3 l, vec4 u, vec4 v) {
    // @slot kinds
}

// Member `object`'s rotation into its frame (a unit quaternion) and its numbers.
void fieldMarchedFrame(int object, out vec4 turn, out vec4 u, out vec4 v) {
    int at = kFieldObjectTexels * object + 3;
    turn = fieldRead(uFieldObjects, uFieldRows.z, at);
    u = fieldRead(uFieldObjects, uFieldRows.z, at + 1);
    v = kFieldArgTexels > 1 ? fieldRead(uFieldObjects, uFieldRows.z, at + 2) : vec4(0.0);
}

// x turned by the unit quaternion q.
vec3 fieldTurn(vec4 q, vec3 x) {
    return x + 2.0 * cross(q.xyz, cross(q.xyz, x) + q.w * x);
}

// Marched member `object` (of kind `kind`, its origin a.xyz) at the field-local q.
float fieldMarchedDistance(vec3 q, vec4 a, int kind, int object) {
    vec4 turn, u, v;
    fieldMarchedFrame(object, turn, u, v);
    return fieldKindDistance(kind, fieldTurn(turn, q - a.xyz), u, v);
}

// Where the ray q0 + rd t (field-local, rd a unit vector; t0 the distance it has
// travelled to q0) first meets marched member `object`, whose bounding sphere is a:
// from where it enters the sphere (at t >= 0), the member's own distance
// sphere-traced in its frame until a step is under the hit test, at most
// kFieldMarchTurns steps and no farther than the sphere's exit; the draw distance
// when it misses. As the march's startHalf: a secondary ray whose first step is at
// its start must come nearer than startLimit of the distance there.
float fieldMarchedEntry(vec3 q0, vec3 rd, vec4 a, int kind, int object, float t0) {
    vec3 oc = q0 - a.xyz;
    float b = dot(oc, rd);
    vec3 c = oc - b * rd;
    float disc = a.w * a.w - dot(c, c);
    float s = sqrt(max(disc, 0.0));
    float tOut = s - b;
    if (disc < 0.0 || tOut < 0.0) {
        return uDrawDist;
    }
    vec4 turn, u, v;
    fieldMarchedFrame(object, turn, u, v);
    vec3 lo = fieldTurn(turn, oc);
    vec3 ld = fieldTurn(turn, rd);
    float t = max(-b - s, 0.0);
    float limit = 10000000000.0;
    for (int i = 0; i < kFieldMarchTurns; i++) {
        float d = fieldKindDistance(kind, lo + ld * t, u, v);
        limit = i == 0 && t == 0.0 && t0 > 0.0 ? startLimit(d) : limit;
        if (d < min(hitThreshold(t0 + t), limit)) {
            return t;
        }
        t += d;
        if (t > tOut) {
            return uDrawDist;
        }
    }
    return uDrawDist;
}
