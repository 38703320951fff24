"""Independent check of a mesh's self-intersections (issue 46), with libigl's
triangle-triangle test (Guigue and Devillers) instead of src/mesh/intersect.fnl:
    python igl_crossings.py MESH.ply [MIN_LENGTH]
Reads the mesh with trimesh (vertices as written, not merged), finds the pairs of
triangles whose boxes overlap (a hash grid of cells twice the mean edge), skips pairs
sharing an edge, and asks igl whether each pair meets and along what segment. A pair
counts when the segment is longer than MIN_LENGTH (default 1e-6 of the mesh's size)
and its points at a quarter, half and three quarters lie on both triangles (igl
returns an edge of one, or two end to end, for some degenerate contacts): pairs sharing one vertex that touch only there give none. Prints
the crossing pairs (no vertex shared) and the folds (one shared), and exits 1 when
there are any. Needs numpy, trimesh and libigl (pip)."""
import sys

import igl
import numpy as np
import trimesh

mesh = trimesh.load(sys.argv[1], process=False)
V = np.asarray(mesh.vertices, dtype=np.float64)
F = np.asarray(mesh.faces, dtype=np.int64)
size = float(np.max(V.max(axis=0) - V.min(axis=0)))
min_length = float(sys.argv[2]) if len(sys.argv) > 2 else 1e-6 * size

lo = V[F].min(axis=1)
hi = V[F].max(axis=1)
edges = np.linalg.norm(V[F[:, 1]] - V[F[:, 0]], axis=1)
cell = 2 * float(edges.mean())
origin = V.min(axis=0)
clo = np.floor((lo - origin) / cell).astype(np.int64)
chi = np.floor((hi - origin) / cell).astype(np.int64)
dims = chi.max(axis=0) + 1
entries = []
for dx in range(int((chi - clo)[:, 0].max()) + 1):
    for dy in range(int((chi - clo)[:, 1].max()) + 1):
        for dz in range(int((chi - clo)[:, 2].max()) + 1):
            c = clo + np.array([dx, dy, dz])
            ok = np.all(c <= chi, axis=1)
            idx = np.nonzero(ok)[0]
            key = c[ok, 0] + dims[0] * (c[ok, 1] + dims[1] * c[ok, 2])
            entries.append(np.stack([key, idx], axis=1))
entries = np.concatenate(entries)
entries = entries[np.lexsort((entries[:, 1], entries[:, 0]))]
pairs = set()
start = 0
keys = entries[:, 0]
bounds = np.nonzero(np.diff(keys))[0] + 1
for group in np.split(entries[:, 1], bounds):
    n = len(group)
    for a in range(n):
        for b in range(a + 1, n):
            s, t = int(group[a]), int(group[b])
            pairs.add((min(s, t), max(s, t)))
crossings = folds = unclear = 0
unclear_shared = {}
longest = 0.0
for s, t in pairs:
    if np.any(lo[s] > hi[t]) or np.any(lo[t] > hi[s]):
        continue
    shared = len(set(F[s].tolist()) & set(F[t].tolist()))
    if shared >= 2:
        continue
    p, q = V[F[s]], V[F[t]]
    hit, coplanar, source, target = igl.tri_tri_intersection_test_3d(
        *[np.ascontiguousarray(x).reshape(1, 3) for x in (p[0], p[1], p[2], q[0], q[1], q[2])])
    if not hit:
        continue
    if coplanar:
        # igl gives no segment for coplanar pairs: the pair counts when they
        # share no vertex, or when one's corner other than the shared one lies
        # inside the other (a coplanar fold).
        length = size if shared == 0 else 0.0
    else:
        length = float(np.linalg.norm(np.asarray(source) - np.asarray(target)))
        # igl's segment for a degenerate contact (an edge of one lying on the
        # other's plane, beyond the shared vertex) can be that edge, or two
        # opposite edges end to end, which each only one triangle holds: the
        # segment's points at a quarter, a half and three quarters must lie on
        # both.
        a, b = np.asarray(source).reshape(3), np.asarray(target).reshape(3)
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            unclear += 1
            unclear_shared[shared] = unclear_shared.get(shared, 0) + 1
            continue
        points = np.array([a + f * (b - a) for f in (0.25, 0.5, 0.75)])
        for tri in (p, q):
            d2, _, _ = igl.point_mesh_squared_distance(points, tri, np.array([[0, 1, 2]]))
            if float(np.max(d2)) > min_length * min_length:
                length = 0.0
    if length > min_length:
        longest = max(longest, length)
        if shared == 0:
            crossings += 1
        else:
            folds += 1
print("%s: %d triangles, %d pairs with overlapping boxes: %d crossing, %d folds at a vertex, longest %.3g; %d pairs igl gave no finite segment for (by vertices shared: %s)"
      % (sys.argv[1], len(F), len(pairs), crossings, folds, longest, unclear,
         ", ".join("%d: %d" % kv for kv in sorted(unclear_shared.items())) or "none"))
sys.exit(1 if crossings or folds else 0)
