"""Mesh the catalog torus with delmesh, check it independently, save it as OFF with the standard
library only and, if matplotlib is installed, draw it.

    PYTHONPATH=build/python python3 python/example.py [OUTPUT_DIRECTORY]
"""
import os
import sys

import delmesh

out_dir = sys.argv[1] if len(sys.argv) > 1 else "."

# Progress lines (about every 0.5 s of refinement) go to stderr; the GIL is released meanwhile.
result = delmesh.mesh(surface="torus", lam=0.06, seed=1,
                      progress=lambda line: print("progress:", line, file=sys.stderr))
print(result)
print("vertices:", result.vertices.shape, result.vertices.dtype,
      "triangles:", result.triangles.shape, result.triangles.dtype)

# The independent checker recomputes topology and quality from the arrays alone.
report = delmesh.check(result.vertices, result.triangles, lam=0.06)
print("genus per component:", report["genus_per_component"],
      "closed manifold:", report["closed_manifold"])
for key in ("min_angle_deg", "max_radius_edge_ratio", "max_roughness_rad"):
    print(f"{key}: {report[key]:.4f} (Theorem 6.1 bound {report['bounds'][key]:.4f}):",
          "pass" if report["pass"][key] else "FAIL")

# OFF with the standard library: repr() writes each coordinate so that it reads back exactly.
off = os.path.join(out_dir, "torus.off")
with open(off, "w") as f:
    f.write(f"OFF\n{len(result.vertices)} {len(result.triangles)} 0\n")
    for x, y, z in result.vertices.tolist():
        f.write(f"{x!r} {y!r} {z!r}\n")
    for a, b, c in result.triangles.tolist():
        f.write(f"3 {a} {b} {c}\n")
print("wrote", off)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no picture")
else:
    figure = plt.figure(figsize=(6, 3))
    axes = figure.add_subplot(projection="3d")
    x, y, z = result.vertices.T
    axes.plot_trisurf(x, y, z, triangles=result.triangles, color="lightsteelblue", edgecolor="black",
                      linewidth=0.2)
    axes.set_box_aspect(result.vertices.max(axis=0) - result.vertices.min(axis=0))
    axes.set_axis_off()
    png = os.path.join(out_dir, "torus.png")
    figure.savefig(png, dpi=150, bbox_inches="tight")
    print("drew", png)
