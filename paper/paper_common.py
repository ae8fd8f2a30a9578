"""Shared helpers of the figure and table scripts: read the experiments' CSV files (a line of
column names, then rows; beside each NAME.csv its metadata NAME.csv.json with the program, the git
revision, the date and the parameters) and OFF meshes.  Nothing else is read: every figure comes
from those files only.  Every figure is written as PDF and PNG."""

import csv
import json
import math
import os


def read_metadata(path):
    """The metadata of the CSV file `path` (PATH.json): program, git, date and the like at the top
    level, with the entries of its "parameters" object added beside them (not replacing any).
    Empty if there is no such file."""
    try:
        with open(path + ".json") as f:
            meta = json.load(f)
    except FileNotFoundError:
        return {}
    if not isinstance(meta, dict):
        raise ValueError(f"{path}.json: not a JSON object")
    for key, value in (meta.get("parameters") or {}).items():
        meta.setdefault(key, value)
    return meta


def read_csv(path):
    """Returns (metadata dict as read_metadata gives it, list of row dicts with numbers converted).
    Raises ValueError for a file whose first line is a '#' comment rather than the column names."""
    with open(path, newline="") as f:
        first = f.readline()
        if first.startswith("#"):
            raise ValueError(f"{path}: first line is a '#' comment, not the column names "
                             "(written by an older experiment program: run it again)")
        f.seek(0)
        rows = []
        for row in csv.DictReader(f):
            rows.append({key: _convert(value) for key, value in row.items()})
    return read_metadata(path), rows


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


def plain_number(value):
    """value with 3 significant digits, without an exponent between 10^-4 and 10^7 (2000, not 2e+03)."""
    text = f"{value:.3g}"
    if "e" in text and 1e-4 <= abs(value) < 1e7:
        text = f"{float(text):f}".rstrip("0").rstrip(".")
    return text


def readable_log_ticks(axis, values=None, max_ticks=8):
    """Labels a log-scale axis (ax.xaxis or ax.yaxis, after plotting) with at most max_ticks
    plain numbers (3 significant digits), at least 1/max_ticks of the axis's log range apart, so
    that no two labels overlap; minor ticks keep no label.  The ticks are `values` (e.g. the 1/λ of
    a sweep) where given, else round numbers (1, 2, 5 × 10^k, finer where the range is narrow)
    within the axis's limits."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

    lo, hi = sorted(axis.get_view_interval())
    if axis.get_scale() != "log" or not lo > 0:
        return
    if values is None:
        values = []
        for mantissas in ((1, 2, 5), (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8), [round(1 + 0.1 * i, 1) for i in range(90)]):
            values = [m * 10.0 ** k for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)
                      for m in mantissas if lo <= m * 10.0 ** k <= hi]
            if len(values) >= 3:
                break
        if len(values) < 2:
            values = [lo, hi]
    values = sorted({v for v in values if v > 0})
    if not values:
        return
    gap = math.log(hi / lo) / max_ticks
    chosen = [values[0]]
    for v in values[1:]:
        if math.log(v / chosen[-1]) >= gap:
            chosen.append(v)
    if chosen[-1] != values[-1]:  # keep the largest value, in place of a too-close neighbour
        chosen[-1 if len(chosen) > 1 else len(chosen):] = [values[-1]]
    axis.set_major_locator(FixedLocator(chosen))
    axis.set_major_formatter(FuncFormatter(lambda v, _: plain_number(v)))
    axis.set_minor_formatter(NullFormatter())


def output_path(out_dir, *parts):
    path = os.path.join(out_dir, *parts)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    return path


def save_figure(fig, out_dir, name, dpi=150):
    """Writes fig as <out_dir>/figures/<name>.pdf and <name>.png (dpi for the PNG and for the
    PDF's rasterized parts), reports both paths and returns them."""
    targets = []
    for kind in ("pdf", "png"):
        target = output_path(out_dir, "figures", f"{name}.{kind}")
        fig.savefig(target, dpi=dpi)
        print("wrote", target)
        targets.append(target)
    return targets
