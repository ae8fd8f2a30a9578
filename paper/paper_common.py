"""Shared helpers of the figure and table scripts: read the experiments' CSV files (first line a
`# key=value ...` comment with the git revision and parameters) and OFF meshes.  Nothing else is
read: every figure comes from those files only."""

import csv
import math
import os


def read_csv(path):
    """Returns (metadata dict from the comment line, list of row dicts with numbers converted)."""
    with open(path, newline="") as f:
        first = f.readline()
        if not first.startswith("#"):
            raise ValueError(f"{path}: first line is not the '# key=value' header")
        meta = {}
        for token in first[1:].split():
            if "=" in token:
                key, value = token.split("=", 1)
                meta[key] = value
        rows = []
        for row in csv.DictReader(f):
            rows.append({key: _convert(value) for key, value in row.items()})
    return meta, rows


def _convert(value):
    if value is None:
        return value
    try:
        if value.lstrip("-").isdigit():
            return int(value)
        return float(value)
    except ValueError:
        return value


def read_off(path):
    """Returns (points as list of (x, y, z), triangles as list of (i, j, k)) of an ASCII OFF file."""
    with open(path) as f:
        tokens = []
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                tokens.extend(line.split())
    if not tokens or not tokens[0].endswith("OFF"):
        raise ValueError(f"{path}: not an OFF file")
    at = 1
    n_points, n_faces = int(tokens[at]), int(tokens[at + 1])
    at += 3
    points = []
    for _ in range(n_points):
        points.append(tuple(float(t) for t in tokens[at:at + 3]))
        at += 3
    triangles = []
    for _ in range(n_faces):
        k = int(tokens[at])
        if k != 3:
            raise ValueError(f"{path}: face with {k} vertices")
        triangles.append(tuple(int(t) for t in tokens[at + 1:at + 4]))
        at += 1 + k
    return points, triangles


def render_mesh(ax, points, triangles, title=None, color=(0.62, 0.74, 0.86), edge_width=0.15):
    """Draws a triangle mesh on a matplotlib 3-D axis with flat Lambert shading and thin edges."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    light = (0.3, 0.4, 0.866)
    norm_l = math.sqrt(sum(c * c for c in light))
    light = tuple(c / norm_l for c in light)
    polygons, colors = [], []
    for i, j, k in triangles:
        a, b, c = points[i], points[j], points[k]
        u = [b[m] - a[m] for m in range(3)]
        v = [c[m] - a[m] for m in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        length = math.sqrt(sum(x * x for x in n)) or 1.0
        shade = 0.5 + 0.5 * abs(sum(n[m] * light[m] for m in range(3)) / length)
        polygons.append((a, b, c))
        colors.append(tuple(min(1.0, ch * shade) for ch in color))
    collection = Poly3DCollection(polygons, facecolors=colors, edgecolors=(0.1, 0.1, 0.15),
                                  linewidths=edge_width)
    ax.add_collection3d(collection)
    lo = [min(p[m] for p in points) for m in range(3)]
    hi = [max(p[m] for p in points) for m in range(3)]
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    extent = [max(hi[m] - lo[m], 1e-9) for m in range(3)]
    try:
        ax.set_box_aspect(extent, zoom=1.25)  # true proportions, filling the panel
    except TypeError:  # matplotlib < 3.6 has no zoom
        ax.set_box_aspect(extent)
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=9)


SURFACE_ORDER = ["sphere", "ellipsoid", "torus", "genus2", "chair", "tanglecube", "metaball", "two_blobs",
                 "thin_handle", "near_sheets"]


def surface_color(name):
    """The same colour for a surface in every figure."""
    import matplotlib.pyplot as plt

    palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    index = SURFACE_ORDER.index(name) if name in SURFACE_ORDER else len(SURFACE_ORDER) + sum(map(ord, name)) % 7
    return palette[index % len(palette)]


def loglog_slope(xs, ys):
    """Least-squares slope of log y against log x."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def output_path(out_dir, *parts):
    path = os.path.join(out_dir, *parts)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    return path


def save_figure(fig, out_dir, name, dpi=150):
    """Writes fig as <out_dir>/figures/<name> and reports the path."""
    target = output_path(out_dir, "figures", name)
    fig.savefig(target, dpi=dpi)
    print("wrote", target)
    return target
