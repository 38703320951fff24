"""The showcase shapes written for fogleman/sdf (numpy), for tools/mesh-vs-fogleman/run.sh.

Each is an equivalent of a scene's finite objects in this repository, written with
fogleman/sdf's own primitives and operations (a smooth union stands in for a chamfer
union, a wireframe box for the box frame, an extruded hexagon for the hex prism, a
torus elongated for a chain link), so its evaluation costs about what the scene's
does there. Coordinates are the scene's (z up).
"""
import numpy as np
from sdf import (box, rounded_box, capped_cylinder, wireframe_box, capsule, sphere,
                 ellipsoid, torus, slab, rounded_cylinder, rounded_cone, hexagon, union,
                 X, Y, Z)


def machined_part():
    holes = union(*[capped_cylinder((x, 0, -1.5), (x, 0, 1.5), 0.35) for x in (-1.6, 0, 1.6)])
    block = box((5, 2, 0.8)).translate((0, 0, 0.4))
    upright = rounded_box((5, 0.6, 2.6), 0.08).translate((0, 0.7, 1.3))
    bracket = (block | upright.k(0.5)) - holes \
        - capped_cylinder((-1.6, -0.3, 1.8), (-1.6, 1.7, 1.8), 0.3) \
        - capped_cylinder((1.6, -0.3, 1.8), (1.6, 1.7, 1.8), 0.3)
    nut = hexagon(0.55).extrude(0.3).translate((0, 0, 0.95)) \
        - capped_cylinder((0, 0, 0.45), (0, 0, 1.45), 0.33)
    flange = rounded_cylinder(0.92, 0.08, 0.5).translate((3.6, -2.2, 0.25)) \
        - capped_cylinder((0, 0, -0.5), (0, 0, 0.5), 0.2).elongate((0.8, 0, 0)).translate((3.6, -2.2, 0.25))
    guard = wireframe_box((1.6, 1.6, 1.6), 0.08).translate((-3.8, -2, 0.8))
    tube = capsule((-1.5, 0, 0), (1.5, 0, 0), 0.3).shell(0.12) & slab(z1=0)
    tube = tube.translate((0, -2.6, 0.3))
    links = []
    for i in range(4):
        link = torus(0.23, 0.07).elongate((0, 0.2, 0))
        if i % 2:
            link = link.rotate(np.pi / 2, X)
        links.append(link.translate((-1.2 + 0.78 * i, -4.2, 0.37)))
    return bracket | nut | flange | guard | tube | union(*links)


def organic():
    body = ellipsoid((1.3, 0.8, 0.7)).translate((0, 0, 1.5))
    head = sphere(0.55, (1.55, 0, 2.25)) | capsule((0.9, 0, 1.8), (1.4, 0, 2.15), 0.3).k(0.25)
    legs = union(*[rounded_cone(0.28, 0.18, 1).translate((x, y, 0.18))
                   for x, y in [(-0.7, -0.5), (-0.7, 0.5), (0.7, -0.5), (0.7, 0.5)]])
    tail = capsule((-1.2, 0, 1.6), (-2, 0, 2.3), 0.12)
    beak = ellipsoid((0.3, 0.11, 0.11)).translate((2.15, 0, 2.2))
    creature = union(body, head, legs, tail, beak, k=0.35)
    eyes = sphere(0.12, (1.92, -0.3, 2.42)) | sphere(0.12, (1.92, 0.3, 2.42))
    creature = creature - eyes.k(0.08)
    rock = ellipsoid((0.9, 0.7, 0.55))

    def bumpy(p):
        q = p - np.array((-2.2, -2, 0.3))
        return rock(q).reshape(-1) + 0.06 * np.sin(9 * q[:, 0]) * np.sin(9 * q[:, 1]) * np.sin(9 * q[:, 2])
    from sdf.d3 import sdf3
    rock3 = sdf3(lambda: bumpy)()
    lens = sphere(1, (0.5, -2.4, -0.1)) & sphere(1, (0.5, -2.4, 1.3)).k(0.1)
    return creature | rock3 | lens


def torus_shape():
    return torus(1, 0.35)


SHAPES = {"machined-part": machined_part, "organic": organic, "torus": torus_shape}
