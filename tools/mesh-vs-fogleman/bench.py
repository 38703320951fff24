"""Times fogleman/sdf's generate() on one shape, region and cell size:
    python bench.py SHAPE x0 y0 z0 x1 y1 z1 STEP
prints 'SECONDS TRIANGLES' (wall seconds of generate, as its own verbose line gives)."""
import sys
import time

from shapes import SHAPES

name = sys.argv[1]
lo = tuple(float(v) for v in sys.argv[2:5])
hi = tuple(float(v) for v in sys.argv[5:8])
step = float(sys.argv[8])
shape = SHAPES[name]()
start = time.time()
points = shape.generate(step=step, bounds=(lo, hi), verbose=False)
print("%.3f %d" % (time.time() - start, len(points) // 3))
