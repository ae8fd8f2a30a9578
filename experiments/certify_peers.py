#!/usr/bin/env python3
"""Gradient-flow certificates of other meshers' outputs, against sampled Hausdorff distances.

For each catalog surface Sigma = {E = 0} (default: torus, genus2, two_blobs, thin_handle, sphere,
ellipsoid) this program makes triangle meshes with three meshers:

  cgal_mesh_3 / cgal_surface_mesher
      CGAL Mesh_3 (facet criteria only) and Surface_mesher, written by
      build/experiments/compare_cgal.  compare_cgal does not take the facet distance on its own:
      its "benchmark" cases SURFACE:H use facet angle 30, facet size (radius) H and facet distance
      H/10 with CGAL's bisection error bound 1e-6 (times the bounding sphere's diameter), so the
      facet distance is chosen through H (--cgal-sizes).  Its "demo" experiment adds the coarse
      radii of --cgal-demo-radii (distance radius/10) at CGAL's default error bound 1e-3, the
      setting users meet.  Setting text: "H=<size> d=<distance> err=<bound>".
  cgal_mesh_3_seeded
      Mesh_3 on the benchmark cases again, with compare_cgal --mesh3-seed-components: CGAL's own
      initial points plus, on every component of Sigma, CGAL's intersections with it near the
      certified critical points of a generic height function (delmesh's seed solve), which
      Mesh_3's rays from one centre can miss (a whole blob of two_blobs).  Setting text adds
      "seeds=<count>".  --no-seeded-mesh-3 skips them.
  marching_cubes
      skimage.measure.marching_cubes (Lewiner) of E sampled at the nodes of a grid over the
      catalog box with N cells along the box's longest side (--mc-resolutions) and cells of about
      the same size along the others.  E is evaluated with numpy from the catalog expression.
      Vertices are mapped to world coordinates, coincident vertices are welded, triangles with a
      repeated vertex dropped, and the (consistent) orientation flipped as a whole if most
      normals disagree with grad E.  A grid on which E does not change sign gives no mesh (logged
      and skipped).  Setting text: "N=<cells>".
  delmesh
      `delmesh mesh --surface NAME` without size bound and with each --delmesh-size-bounds.

Each mesh is then checked by `delmesh check MESH --surface NAME --certify --json` twice:
with --method gradient-flow and with --method auto, each with --time-limit (--timeout seconds).

Columns of the table (<out-dir>/certify_peers.md and .csv; the CSV has more):

  vertices, genus      from `delmesh check --json` (vertices, genus_per_component; "-" where
                       the genus is not defined, e.g. a non-manifold mesh).  "ok" says whether it
                       equals the catalog's genus_per_component.
  verdict, reason      gradient_flow.status and gradient_flow.reason of the gradient-flow run
                       (the reason only when it is not certified).
  bound                the certified two-sided Hausdorff bound gradient_flow.hausdorff_upper_bound
                       (an upper bound of d_H(mesh, Sigma), proved by delmesh), and bound/diag, the
                       same relative to the box diagonal (gradient_flow.hausdorff_relative).
  sampled              a sampled two-sided Hausdorff distance max(m->S, S->m), computed here:
                       m->S  the largest distance from a point of a barycentric grid on every
                             triangle (k subdivisions per edge, k a multiple of 3 so centroids
                             are included, chosen so the grid spacing is about the Sigma sample's
                             spacing, at most --max-mesh-samples points) to Sigma.  Each point x
                             is moved onto Sigma by Newton steps x <- x - E grad E / |grad E|^2
                             and then to a foot point p with x - p parallel to grad E(p)
                             (alternating projection onto the tangent plane at p and Newton back
                             onto Sigma); its distance is min(|x - p|, distance to the nearest
                             point of the Sigma sample).  Both are distances to points of Sigma,
                             so each sample's distance is never below its true distance to Sigma
                             (and equals it when the foot point is the nearest point).
                       S->m  the largest exact point-to-triangle distance from a point of a dense
                             sample of Sigma to the mesh.  The Sigma sample is every node of a
                             grid with --sigma-cells cells along the box's longest side whose
                             first-order distance |E|/|grad E| is below one cell, projected onto
                             Sigma by Newton steps (points that do not converge, or move more than
                             three cells, are dropped).  The nearest triangles are found with a
                             scipy cKDTree over triangle centroids, then every triangle whose
                             centroid is close enough to matter is measured exactly.
                       Both maxima are over finite samples, so "sampled" estimates d_H from
                       below, up to the covering radius of the samples (about one sampling
                       spacing, printed in the report) and up to the m->S foot points, which
                       can only overestimate a sample's distance.  A certified bound below the
                       sampled value by more than 1e-9 of the diagonal is flagged UNSOUND.
  ratio                bound / sampled.  Above 10 it is flagged LOOSE.
  cert s               gradient_flow.seconds (the certificate's own time; the CSV also has the
                       wall time of the whole `delmesh check` process).
  auto                 topology.verdict and topology.method of the --method auto run.

A mesh whose genus differs from the catalog's and that is certified is flagged UNSOUND as well.

After the table, certify_peers.md has three sections:
  Acceptance figures   read off the rows: for torus, genus2 and two_blobs the seeded Mesh_3 rows at
                       facet distance <= diagonal/200 (vertices, components, verdict, bound,
                       sampled); the coarsest certified marching-cubes torus; how many
                       wrong-topology meshes either method certified; the rows whose bound is below
                       the sampled distance and the largest bound/sampled.
  default outputs      `delmesh mesh --surface NAME` for each surface of --catalog (default every
                       catalog surface), checked with `--certify --method both`: each method's
                       verdict and whether they agree.
  cost                 `delmesh mesh --surface S --size-bound H` (--cost-surface, --cost-size-bound)
                       and the gradient-flow check of its output, --cost-runs runs each: the process
                       wall times, the statistics' and the certificate's own seconds, and the ratio
                       of the certificate's to the mesh run's (medians).
Meshes are kept under <out-dir>/meshes, the check reports under <out-dir>/checks.

Needs numpy, scipy and scikit-image (e.g. /usr/bin/python3 on the project's machine; Debian
package python3-skimage); sympy, where present, gives the exact gradient of E, else central
differences are used.  Runs one process at a time.

Example:
  /usr/bin/python3 experiments/certify_peers.py --out-dir out/certify_peers
  /usr/bin/python3 experiments/certify_peers.py --quick --out-dir out/certify_peers_quick
"""

import argparse
import csv
import glob
import json
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

try:
    from scipy.spatial import cKDTree
except ImportError:  # pragma: no cover - the report needs it
    sys.exit("certify_peers.py needs scipy (scipy.spatial.cKDTree); run it with /usr/bin/python3")
try:
    from skimage.measure import marching_cubes
except ImportError:  # pragma: no cover
    sys.exit("certify_peers.py needs scikit-image (Debian: apt-get install python3-skimage)")

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SURFACES = "torus,genus2,two_blobs,thin_handle,sphere,ellipsoid"


# --- the implicit function --------------------------------------------------------------------
class Implicit:
    """E and grad E of a catalog expression, vectorised over numpy arrays."""

    NAMES = {"exp": np.exp, "sqrt": np.sqrt, "sin": np.sin, "cos": np.cos, "log": np.log,
             "Pi": np.pi, "pi": np.pi}

    def __init__(self, expression, box):
        self.expression = expression
        self.box = np.asarray(box, dtype=float).reshape(3, 2)
        self.diagonal = float(np.linalg.norm(self.box[:, 1] - self.box[:, 0]))
        self.text = expression.replace("^", "**")
        self.code = compile(self.text, "<E>", "eval")
        self.gradient_source = "central differences"
        self._gradient = None
        try:
            import sympy
            x, y, z = sympy.symbols("x y z")
            local = {"x": x, "y": y, "z": z, "Pi": sympy.pi, "exp": sympy.exp, "sqrt": sympy.sqrt,
                     "sin": sympy.sin, "cos": sympy.cos, "log": sympy.log}
            e = sympy.sympify(self.text, locals=local)
            self._gradient = [sympy.lambdify((x, y, z), sympy.diff(e, v), "numpy") for v in (x, y, z)]
            self.gradient_source = "sympy"
        except Exception:
            self._gradient = None

    def value(self, p):
        p = np.asarray(p, dtype=float)
        names = dict(self.NAMES, x=p[..., 0], y=p[..., 1], z=p[..., 2])
        return np.broadcast_to(eval(self.code, {"__builtins__": {}}, names), p.shape[:-1]).astype(float)

    def gradient(self, p):
        p = np.asarray(p, dtype=float)
        if self._gradient is not None:
            parts = [np.broadcast_to(np.asarray(g(p[..., 0], p[..., 1], p[..., 2]), dtype=float), p.shape[:-1])
                     for g in self._gradient]
            return np.stack(parts, axis=-1)
        h = 1e-6 * self.diagonal
        out = np.empty(p.shape)
        for k in range(3):
            step = np.zeros(3)
            step[k] = h
            out[..., k] = (self.value(p + step) - self.value(p - step)) / (2 * h)
        return out

    def newton(self, p, iterations=40, max_step=None):
        """Newton steps p <- p - E grad E / |grad E|^2 (each at most max_step long); returns the
        points and whether each converged (|E|/|grad E| below 1e-12 of the diagonal)."""
        p = np.array(p, dtype=float)
        max_step = 0.05 * self.diagonal if max_step is None else max_step
        tolerance = 1e-12 * self.diagonal
        active = np.ones(len(p), dtype=bool)
        converged = np.zeros(len(p), dtype=bool)
        for _ in range(iterations):
            idx = np.nonzero(active)[0]
            if idx.size == 0:
                break
            q = p[idx]
            e = self.value(q)
            g = self.gradient(q)
            gg = np.einsum("ij,ij->i", g, g)
            ok = gg > 0
            step = np.zeros_like(q)
            step[ok] = (e[ok] / gg[ok])[:, None] * g[ok]
            length = np.linalg.norm(step, axis=1)
            scale = np.where(length > max_step, max_step / np.maximum(length, 1e-300), 1.0)
            p[idx] = q - step * scale[:, None]
            done = ok & (np.abs(e) / np.sqrt(np.where(ok, gg, 1.0)) < tolerance)
            converged[idx[done]] = True
            active[idx[done | ~ok]] = False
        # A last residual test for the points that ran out of iterations.
        idx = np.nonzero(~converged)[0]
        if idx.size:
            e = self.value(p[idx])
            gn = np.linalg.norm(self.gradient(p[idx]), axis=1)
            converged[idx] = (gn > 0) & (np.abs(e) < 1e-10 * self.diagonal * np.maximum(gn, 1e-300))
        return p, converged

    def foot_points(self, x, rounds=8):
        """Points p of Sigma with x - p along grad E(p) (local nearest points), found by Newton
        projection and then alternating projection onto the tangent plane at p and Newton back
        onto Sigma; returns p and whether the last projection converged."""
        p, ok = self.newton(x)
        for _ in range(rounds):
            g = self.gradient(p)
            n = g / np.maximum(np.linalg.norm(g, axis=1), 1e-300)[:, None]
            q = x - np.einsum("ij,ij->i", x - p, n)[:, None] * n
            p_new, ok_new = self.newton(q, iterations=10)
            take = ok_new
            p[take] = p_new[take]
            ok = ok | ok_new
        return p, ok


# --- geometry ---------------------------------------------------------------------------------
def point_triangle_distance(p, a, b, c):
    """Exact Euclidean distance from each point p[i] to triangle (a[i], b[i], c[i])."""
    ab, ac = b - a, c - a
    ap, bp, cp = p - a, p - b, p - c
    dot = lambda u, v: np.einsum("ij,ij->i", u, v)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    vc = d1 * d4 - d3 * d2
    vb = d5 * d2 - d1 * d6
    va = d3 * d6 - d5 * d4
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        q = a + ab * (vb / denom)[:, None] + ac * (vc / denom)[:, None]
        # Regions in reverse order of precedence: the last assignment wins.
        m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        q[m] = (b + (c - b) * w[:, None])[m]
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        w = d2 / (d2 - d6)
        q[m] = (a + ac * w[:, None])[m]
        m = (d6 >= 0) & (d5 <= d6)
        q[m] = c[m]
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        v = d1 / (d1 - d3)
        q[m] = (a + ab * v[:, None])[m]
        m = (d3 >= 0) & (d4 <= d3)
        q[m] = b[m]
        m = (d1 <= 0) & (d2 <= 0)
        q[m] = a[m]
    d = np.linalg.norm(p - q, axis=1)
    bad = ~np.isfinite(d)
    if bad.any():  # zero-area triangles: the nearest of the three edges
        d[bad] = np.min([segment_distance(p[bad], s[bad], t[bad]) for s, t in ((a, b), (b, c), (c, a))], axis=0)
    return d


def segment_distance(p, s, t):
    st = t - s
    ll = np.einsum("ij,ij->i", st, st)
    u = np.clip(np.einsum("ij,ij->i", p - s, st) / np.maximum(ll, 1e-300), 0.0, 1.0)
    return np.linalg.norm(p - (s + st * u[:, None]), axis=1)


def distance_to_mesh(points, vertices, triangles, chunk=20000):
    """Exact distance from each point to the triangle mesh: the nearest centroid's triangle gives
    an upper bound r; every triangle within r has its centroid within r + (the largest
    centroid-to-vertex distance), and those are all measured."""
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    centroids = (a + b + c) / 3
    reach = float(np.max(np.linalg.norm(np.stack([a, b, c]) - centroids[None], axis=2)))
    tree = cKDTree(centroids)
    out = np.empty(len(points))
    for start in range(0, len(points), chunk):
        p = points[start:start + chunk]
        _, nearest = tree.query(p)
        upper = point_triangle_distance(p, a[nearest], b[nearest], c[nearest])
        candidates = tree.query_ball_point(p, upper + reach + 1e-12)
        counts = np.fromiter((len(x) for x in candidates), dtype=np.int64, count=len(p))
        tri = np.fromiter((t for x in candidates for t in x), dtype=np.int64, count=int(counts.sum()))
        owner = np.repeat(np.arange(len(p)), counts)
        best = upper.copy()
        for s in range(0, len(tri), 2_000_000):
            o, t = owner[s:s + 2_000_000], tri[s:s + 2_000_000]
            d = point_triangle_distance(p[o], a[t], b[t], c[t])
            np.minimum.at(best, o, d)
        out[start:start + chunk] = best
    return out


def grid_axes(box, cells_longest):
    """Node coordinates along each axis: cells_longest cells along the longest side, cells of
    about the same size along the others, the nodes spanning the box exactly."""
    lengths = box[:, 1] - box[:, 0]
    h = lengths.max() / cells_longest
    return [np.linspace(box[k, 0], box[k, 1], max(2, int(math.ceil(lengths[k] / h - 1e-9))) + 1) for k in range(3)]


def sample_sigma(E, cells_longest):
    """Points of Sigma: grid nodes within about one cell of it, projected by Newton's method."""
    xs, ys, zs = grid_axes(E.box, cells_longest)
    h = max(xs[1] - xs[0], ys[1] - ys[0], zs[1] - zs[0])
    Y, Z = np.meshgrid(ys, zs, indexing="ij")
    near = []
    for x in xs:
        p = np.stack([np.full(Y.shape, x), Y, Z], axis=-1).reshape(-1, 3)
        e = E.value(p)
        g = np.linalg.norm(E.gradient(p), axis=1)
        keep = np.abs(e) < h * g
        near.append(p[keep])
    start = np.concatenate(near) if near else np.zeros((0, 3))
    projected, ok = E.newton(start)
    ok &= np.linalg.norm(projected - start, axis=1) < 3 * h
    return projected[ok], h


def surface_to_mesh(E, sigma, vertices, triangles):
    return float(np.max(distance_to_mesh(sigma, vertices, triangles))) if len(sigma) else float("nan")


def mesh_to_surface(E, sigma_tree, spacing, vertices, triangles, max_samples):
    """The largest distance to Sigma over a barycentric grid on every triangle (see the module
    docstring); returns it and the grid's subdivision k."""
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    longest = float(max(np.linalg.norm(b - a, axis=1).max(), np.linalg.norm(c - b, axis=1).max(),
                        np.linalg.norm(a - c, axis=1).max()))
    k = 3 * max(1, int(math.ceil(longest / spacing / 3)))
    while k > 3 and len(triangles) * (k + 1) * (k + 2) // 2 > max_samples:
        k -= 3
    weights = np.array([(i, j, k - i - j) for i in range(k + 1) for j in range(k + 1 - i)], dtype=float) / k
    worst = 0.0
    per_chunk = max(1, 400000 // len(weights))
    for s in range(0, len(triangles), per_chunk):
        x = (weights[None, :, 0:1] * a[s:s + per_chunk, None] + weights[None, :, 1:2] * b[s:s + per_chunk, None]
             + weights[None, :, 2:3] * c[s:s + per_chunk, None]).reshape(-1, 3)
        d = sigma_tree.query(x)[0]
        p, ok = E.foot_points(x)
        foot = np.where(ok, np.linalg.norm(x - p, axis=1), np.inf)
        worst = max(worst, float(np.max(np.minimum(d, foot))))
    return worst, k


# --- mesh files -------------------------------------------------------------------------------
def read_off(path):
    with open(path) as f:
        tokens = [t for line in f for t in line.split("#")[0].split()]
    if tokens[0] != "OFF":
        raise ValueError(f"{path}: not an OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    vertices = np.array(tokens[at:at + 3 * nv], dtype=float).reshape(nv, 3)
    at += 3 * nv
    triangles = []
    for _ in range(nf):
        n = int(tokens[at])
        face = [int(t) for t in tokens[at + 1:at + 1 + n]]
        at += 1 + n
        for i in range(1, n - 1):
            triangles.append((face[0], face[i], face[i + 1]))
    return vertices, np.array(triangles, dtype=np.int64).reshape(-1, 3)


def write_off(path, vertices, triangles):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(triangles)} 0\n")
        np.savetxt(f, vertices, fmt="%.17g")
        np.savetxt(f, np.hstack([np.full((len(triangles), 1), 3), triangles]), fmt="%d")


def marching_cubes_mesh(E, cells_longest):
    """Marching cubes of E on the grid; returns world vertices, triangles and notes."""
    xs, ys, zs = grid_axes(E.box, cells_longest)
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    volume = E.value(np.stack([X, Y, Z], axis=-1))
    spacing = (xs[1] - xs[0], ys[1] - ys[0], zs[1] - zs[0])
    verts, faces, _, _ = marching_cubes(volume, level=0.0, spacing=spacing, allow_degenerate=False)
    verts = verts + np.array([xs[0], ys[0], zs[0]])
    # Weld vertices that coincide (up to 1e-12 of the diagonal).
    key = np.round(verts / (1e-12 * E.diagonal)).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    welded = len(verts) - len(first)
    verts = verts[first]
    faces = inverse.reshape(-1)[faces]
    keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 2] != faces[:, 0])
    dropped = int((~keep).sum())
    faces = faces[keep]
    used = np.unique(faces)
    remap = np.full(len(verts), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    verts, faces = verts[used], remap[faces]
    # One orientation for the whole mesh: outward along grad E where most triangles agree.
    a, b, c = (verts[faces[:, k]] for k in range(3))
    normals = np.cross(b - a, c - a)
    agree = np.einsum("ij,ij->i", normals, E.gradient((a + b + c) / 3)) > 0
    if agree.mean() < 0.5:
        faces = faces[:, [0, 2, 1]]
        agree = ~agree
    notes = f"welded {welded}, dropped {dropped}, along grad E {agree.mean():.3f}"
    return verts, faces, notes


# --- running delmesh --------------------------------------------------------------------------
def run_json(command, timeout):
    """Runs a command, returns (parsed JSON of stdout or None, exit code, wall seconds, stderr)."""
    start = time.monotonic()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "timeout", time.monotonic() - start, ""
    except OSError as e:  # e.g. the binary is being relinked by a build
        return None, f"error: {e.strerror}", time.monotonic() - start, str(e)
    seconds = time.monotonic() - start
    try:
        return json.loads(done.stdout), done.returncode, seconds, done.stderr
    except json.JSONDecodeError:
        return None, done.returncode, seconds, done.stderr


def certify(delmesh, mesh, surface, method, timeout, report_path):
    command = [delmesh, "check", mesh, "--surface", surface, "--certify", "--method", method, "--json",
               "--time-limit", str(timeout)]
    report, code, seconds, stderr = run_json(command, timeout + 60)
    with open(report_path, "w") as f:
        json.dump({"command": command, "exit_code": code, "wall_seconds": seconds, "stderr": stderr,
                   "report": _without_triangle_bounds(report)}, f, indent=1)
    return report, code, seconds, command


def _without_triangle_bounds(report):
    if not isinstance(report, dict):
        return report
    out = dict(report)
    if isinstance(out.get("gradient_flow"), dict):
        flow = dict(out["gradient_flow"])
        bounds = flow.pop("triangle_distance_bounds", None)
        if isinstance(bounds, list):
            finite = [b for b in bounds if isinstance(b, (int, float))]
            flow["triangle_distance_bounds_max"] = max(finite) if finite else None
        out["gradient_flow"] = flow
    return out


# --- the mesh list ----------------------------------------------------------------------------
def run_compare_cgal(args, surface, out, extra, log):
    """Runs compare_cgal for one surface into `out` with the benchmark cases of --cgal-sizes and
    the arguments `extra`; returns [(method, setting, path, radius)] of the meshes it wrote."""
    os.makedirs(out, exist_ok=True)
    cases = ",".join(f"{surface}:{h:g}" for h in args.cgal_sizes)
    command = [args.compare_cgal, "--skip-delmesh", "--cases", cases, *extra, "--out-dir", out]
    log(" ".join(command))
    try:
        subprocess.run(command, capture_output=True, text=True, timeout=args.timeout, check=True)
    except (subprocess.CalledProcessError, subprocess.TimeoutExpired) as e:
        log(f"compare_cgal failed for {surface}: {e}")
        return []
    found = []
    pattern = re.compile(r"compare_(benchmark|demo)_" + re.escape(surface) +
                         r"_(mesh_3|surface_mesher)_angle_[^_]+_radius_([^_]+)_distance_([^_]+)"
                         r"(?:_relative_error_bound_([^_]+))?_.*?(seeded_\d+)?\.off$")
    for path in sorted(glob.glob(os.path.join(out, "meshes", "*.off"))):
        m = pattern.match(os.path.basename(path))
        if not m:
            continue
        _, method, radius, distance, error, seeded = m.groups()
        setting = f"H={float(radius):g} d={float(distance):g} err={error or '1e-3'}"
        if seeded:
            method += "_seeded"
            setting += f" seeds={seeded.split('_')[1]}"
        found.append((method, setting, path, float(radius)))
    return found


def cgal_meshes(args, surface, mesh_dir, log):
    """Runs compare_cgal for one surface: its benchmark and demo experiments, and (unless
    --no-seeded-mesh-3) the benchmark's Mesh_3 again with --mesh3-seed-components (mesher
    cgal_mesh_3_seeded); returns [(mesher, setting, path)]."""
    found = run_compare_cgal(args, surface, os.path.join(mesh_dir, "cgal", surface),
                             ["--experiments", "benchmark,demo", "--demo-surfaces", surface, "--coarse-radii",
                              *[f"{r:g}" for r in args.cgal_demo_radii]], log)
    if not args.no_seeded_mesh_3:
        seeded = run_compare_cgal(args, surface, os.path.join(mesh_dir, "cgal_seeded", surface),
                                  ["--experiments", "benchmark", "--mesh3-seed-components"], log)
        found += [f for f in seeded if f[0] == "mesh_3_seeded"]
    order = {"mesh_3": 0, "mesh_3_seeded": 1, "surface_mesher": 2}
    # Coarse first; Mesh_3, seeded Mesh_3, Surface_mesher.
    found.sort(key=lambda t: (order[t[0]], -t[3], "err=1e-3" in t[1]))
    return [(f"cgal_{m}", s, p) for m, s, p, _ in found]


def delmesh_meshes(args, surface, mesh_dir, log):
    found = []
    for bound in [None] + list(args.delmesh_size_bounds):
        stem = os.path.join(mesh_dir, f"delmesh_{surface}_{'none' if bound is None else f'{bound:g}'}")
        command = [args.delmesh, "mesh", "--surface", surface, "--out", stem + ".off", "--stats", stem + ".json",
                   "--quiet", "--time-limit", str(args.timeout)]
        if bound is not None:
            command += ["--size-bound", f"{bound:g}"]
        log(" ".join(command))
        try:
            done = subprocess.run(command, capture_output=True, text=True, timeout=args.timeout + 60)
            code = done.returncode
        except subprocess.TimeoutExpired:
            code = "timeout"
        if os.path.exists(stem + ".off"):
            setting = "no size bound" if bound is None else f"size_bound={bound:g}"
            if code != 0:
                setting += f" (exit {code})"
            found.append(("delmesh", setting, stem + ".off"))
    return found


def mc_meshes(args, surface, E, mesh_dir, log):
    found = []
    for n in args.mc_resolutions:
        path = os.path.join(mesh_dir, f"mc_{surface}_{n}.off")
        try:
            verts, faces, notes = marching_cubes_mesh(E, n)
        except ValueError as e:  # no sign change of E on the grid: no mesh
            log(f"marching cubes {surface} N={n}: no mesh ({e})")
            continue
        write_off(path, verts, faces)
        log(f"marching cubes {surface} N={n}: {len(verts)} vertices, {len(faces)} triangles, {notes}")
        found.append(("marching_cubes", f"N={n}", path))
    return found


# --- the table --------------------------------------------------------------------------------
COLUMNS = ["surface", "mesher", "setting", "vertices", "triangles", "components", "genus", "expected_genus", "genus_ok",
           "closed_manifold", "gf_verdict", "gf_reason", "gf_location", "gf_bound", "gf_bound_relative",
           "gf_epsilon", "gf_min_gradient", "gf_seconds", "gf_wall_seconds", "gf_exit",
           "auto_verdict", "auto_method", "auto_reason", "auto_bound", "auto_wall_seconds",
           "sampled_mesh_to_surface", "sampled_surface_to_mesh", "sampled_hausdorff", "barycentric_k",
           "sigma_samples", "sigma_spacing", "ratio", "flags", "mesh", "gf_command"]


def fmt(value, digits=3):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def write_tables(rows, out_dir, header):
    with open(os.path.join(out_dir, "certify_peers.csv"), "w", newline="") as f:
        f.write("# " + header + "\n")
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in COLUMNS})
    lines = [f"<!-- {header} -->", "",
             "| surface | mesher | setting | vertices | genus | gradient-flow verdict (reason) | bound | bound/diag "
             "| sampled | ratio | cert s | auto | flags |",
             "|---|---|---|---:|---|---|---:|---:|---:|---:|---:|---|---|"]
    for r in rows:
        verdict = r["gf_verdict"] or "-"
        if verdict != "certified" and r.get("gf_reason"):
            verdict += f" ({r['gf_reason']})"
        genus = r["genus"] + ("" if r["genus_ok"] else f" (expected {r['expected_genus']})")
        auto = r["auto_verdict"] or "-"
        if r.get("auto_method"):
            auto += f" ({r['auto_method']})"
        lines.append("| " + " | ".join([
            r["surface"], r["mesher"], r["setting"], fmt(r["vertices"]), genus, verdict.replace("|", "/"),
            fmt(r["gf_bound"]), fmt(r["gf_bound_relative"]), fmt(r["sampled_hausdorff"]), fmt(r["ratio"]),
            fmt(r["gf_seconds"]), auto, r["flags"]]) + " |")
    with open(os.path.join(out_dir, "certify_peers.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return "\n".join(lines)


def summary(rows):
    out = []
    bad = [r for r in rows if "UNSOUND" in r["flags"]]
    out.append(f"UNSOUND rows: {len(bad)}")
    for r in bad:
        out.append(f"  {r['surface']} {r['mesher']} {r['setting']}: {r['flags']}; {r['mesh']}; {r['gf_command']}")
    wrong = [r for r in rows if not r["genus_ok"]]
    out.append(f"wrong-topology meshes: {len(wrong)} ("
               + ", ".join(f"{r['surface']} {r['mesher']} {r['setting']}: gf {r['gf_verdict']}, auto {r['auto_verdict']}"
                           for r in wrong) + ")")
    loose = [r for r in rows if "LOOSE" in r["flags"]]
    out.append(f"bound > 10x sampled: {len(loose)} ("
               + ", ".join(f"{r['surface']} {r['mesher']} {r['setting']} {fmt(r['ratio'])}" for r in loose) + ")")
    ratios = [r["ratio"] for r in rows if isinstance(r["ratio"], float) and math.isfinite(r["ratio"])]
    if ratios:
        out.append(f"ratio bound/sampled over {len(ratios)} certified meshes: min {min(ratios):.3g}, "
                   f"median {float(np.median(ratios)):.3g}, max {max(ratios):.3g}")
    missed = [r for r in rows if r["genus_ok"] and r["gf_verdict"] != "certified"]
    out.append(f"right-topology meshes not certified by gradient-flow: {len(missed)}")
    for r in missed:
        out.append(f"  {r['surface']} {r['mesher']} {r['setting']}: {r['gf_verdict']}: {r['gf_reason']}"
                   f" (auto: {r['auto_verdict']})")
    return "\n".join(out)


def catalog_both(args, names, out_dir, log):
    """delmesh's default output of each catalog surface, checked with --method both; returns the
    Markdown section and its rows."""
    mesh_dir = os.path.join(out_dir, "catalog")
    os.makedirs(mesh_dir, exist_ok=True)
    rows = []
    for name in names:
        stem = os.path.join(mesh_dir, name)
        command = [args.delmesh, "mesh", "--surface", name, "--out", stem + ".off", "--quiet",
                   "--time-limit", str(args.timeout)]
        log(" ".join(command))
        subprocess.run(command, capture_output=True, text=True, timeout=args.timeout + 60)
        report, code, wall, _ = certify(args.delmesh, stem + ".off", name, "both", args.timeout,
                                        stem + ".both.json")
        report = report if isinstance(report, dict) else {}
        rd = report.get("certificate") or {}
        gf = report.get("gradient_flow") or {}
        topo = report.get("topology") or {}
        row = {"surface": name, "vertices": report.get("vertices"),
               "genus": json.dumps(report.get("genus_per_component")), "rd": rd.get("status") or f"exit {code}",
               "gf": gf.get("status") or f"exit {code}", "gf_reason": gf.get("reason") or "",
               "bound": gf.get("hausdorff_upper_bound"), "relative": gf.get("hausdorff_relative"),
               "rd_seconds": rd.get("seconds"), "gf_seconds": gf.get("seconds"), "verdict": topo.get("verdict"),
               "reason": topo.get("reason") or ""}
        row["agree"] = row["rd"] == row["gf"]
        rows.append(row)
        log(f"catalog {name}: {row['vertices']} vertices, restricted-delaunay {row['rd']}, gradient-flow {row['gf']}"
            f" {row['gf_reason']}, both: {row['verdict']} ({row['reason']})")
    lines = ["## delmesh's default output of every catalog surface, `--method both`", "",
             "`delmesh mesh --surface NAME` (no size bound), then `delmesh check OUT --surface NAME --certify "
             "--method both`.", "",
             "| surface | vertices | genus | restricted-delaunay | gradient-flow | agree | bound | bound/diag "
             "| RD s | GF s | verdict |", "|---|---:|---|---|---|---|---:|---:|---:|---:|---|"]
    for r in rows:
        gf = r["gf"] + (f" ({r['gf_reason']})" if r["gf_reason"] else "")
        lines.append("| " + " | ".join([r["surface"], fmt(r["vertices"]), r["genus"], r["rd"], gf.replace("|", "/"),
                                        "yes" if r["agree"] else "NO", fmt(r["bound"]), fmt(r["relative"]),
                                        fmt(r["rd_seconds"]), fmt(r["gf_seconds"]),
                                        f"{r['verdict']} ({r['reason']})".replace("|", "/")]) + " |")
    agree = sum(r["agree"] for r in rows)
    both = sum(r["rd"] == "certified" and r["gf"] == "certified" for r in rows)
    lines += ["", f"Both methods agree on {agree} of {len(rows)} surfaces; both certified on {both}."]
    return "\n".join(lines), rows


def cost(args, out_dir, log):
    """Seconds of `delmesh mesh --surface S --size-bound H` and of the gradient-flow certificate of
    its output, --cost-runs runs each (alternating); returns the Markdown section."""
    mesh_dir = os.path.join(out_dir, "cost")
    os.makedirs(mesh_dir, exist_ok=True)
    stem = os.path.join(mesh_dir, f"{args.cost_surface}_{args.cost_size_bound:g}")
    mesh_wall, mesh_seconds, check_wall, cert_seconds, vertices, status = [], [], [], [], None, None
    for run in range(args.cost_runs):
        command = [args.delmesh, "mesh", "--surface", args.cost_surface, "--size-bound", f"{args.cost_size_bound:g}",
                   "--out", stem + ".off", "--stats", stem + ".json", "--quiet"]
        start = time.monotonic()
        subprocess.run(command, capture_output=True, text=True, timeout=args.timeout + 60, check=True)
        mesh_wall.append(time.monotonic() - start)
        with open(stem + ".json") as f:
            stats = json.load(f)
        mesh_seconds.append(stats.get("seconds"))
        report, code, wall, check_command = certify(args.delmesh, stem + ".off", args.cost_surface, "gradient-flow",
                                                    args.timeout, stem + f".check{run + 1}.json")
        flow = report.get("gradient_flow", {}) if isinstance(report, dict) else {}
        check_wall.append(wall)
        cert_seconds.append(flow.get("seconds"))
        vertices = report.get("vertices") if isinstance(report, dict) else None
        status = flow.get("status")
        log(f"cost run {run + 1}: mesh {mesh_wall[-1]:.2f} s wall ({fmt(mesh_seconds[-1])} s in statistics), "
            f"{vertices} vertices; gradient-flow {status} in {fmt(cert_seconds[-1])} s (check wall {wall:.2f} s)")
    med = lambda v: float(np.median([x for x in v if isinstance(x, (int, float))])) if v else float("nan")
    ratio_cert = med(cert_seconds) / med(mesh_wall)
    ratio_wall = med(check_wall) / med(mesh_wall)
    lines = ["## Cost of the certificate", "",
             f"`delmesh mesh --surface {args.cost_surface} --size-bound {args.cost_size_bound:g}` and "
             f"`delmesh check OUT --surface {args.cost_surface} --certify --method gradient-flow --json`, "
             f"{args.cost_runs} runs each (alternating); medians. Mesh: {vertices} vertices, gradient-flow {status}.", "",
             "| | run seconds | median |", "|---|---|---:|",
             f"| delmesh mesh (process wall) | {', '.join(f'{x:.2f}' for x in mesh_wall)} | {med(mesh_wall):.2f} |",
             f"| delmesh mesh (statistics seconds) | {', '.join(fmt(x) for x in mesh_seconds)} | {fmt(med(mesh_seconds))} |",
             f"| gradient-flow certificate (gradient_flow.seconds) | {', '.join(fmt(x) for x in cert_seconds)} "
             f"| {fmt(med(cert_seconds))} |",
             f"| delmesh check (process wall: reading, checks, certificate) | {', '.join(f'{x:.2f}' for x in check_wall)} "
             f"| {med(check_wall):.2f} |", "",
             f"Certificate / mesh: {ratio_cert:.3g} (certificate seconds), {ratio_wall:.3g} (check process wall) "
             f"(target <= 2)."]
    return "\n".join(lines), {"ratio_cert": ratio_cert, "ratio_wall": ratio_wall, "vertices": vertices,
                              "status": status}


def acceptance(rows, catalog_rows, cost_result, catalog):
    """The Markdown section that reads the acceptance figures off the rows."""
    lines = ["## Acceptance figures", ""]
    for surface in ("torus", "genus2", "two_blobs"):
        if surface not in catalog:
            continue
        diag = Implicit(catalog[surface]["equation"], catalog[surface]["box"]).diagonal
        fine = [r for r in rows if r["surface"] == surface and r["mesher"] == "cgal_mesh_3_seeded"
                and float(re.search(r"d=([^ ]+)", r["setting"]).group(1)) <= diag / 200]
        for r in fine:
            lines.append(f"- {surface} Mesh_3 seeded {r['setting']} (facet distance <= diag/200 = {diag / 200:.4g}): "
                         f"{fmt(r['vertices'])} vertices, {r['components']} components, genus {r['genus']}, "
                         f"gradient-flow {r['gf_verdict']}, bound {fmt(r['gf_bound'])}, sampled "
                         f"{fmt(r['sampled_hausdorff'])}")
        if not fine:
            lines.append(f"- {surface}: no seeded Mesh_3 row at facet distance <= diag/200")
    mc = sorted((int(r["setting"][2:]), r["gf_verdict"]) for r in rows
                if r["surface"] == "torus" and r["mesher"] == "marching_cubes")
    certified_n = [n for n, v in mc if v == "certified"]
    lines.append(f"- marching-cubes torus: coarsest certified N = {certified_n[0] if certified_n else '-'} "
                 f"(verdicts: {', '.join(f'N={n} {v}' for n, v in mc)})")
    wrong = [r for r in rows if not r["genus_ok"]]
    wrong_certified = [r for r in wrong if r["gf_verdict"] == "certified" or r["auto_verdict"] == "certified"]
    lines.append(f"- wrong-topology meshes: {len(wrong)}, certified by either method: {len(wrong_certified)}")
    unsound = [r for r in rows if "UNSOUND" in r["flags"]]
    ratios = [r["ratio"] for r in rows if isinstance(r["ratio"], float) and math.isfinite(r["ratio"])]
    lines.append(f"- certified bound below the sampled distance: {len(unsound)} rows; bound/sampled over "
                 f"{len(ratios)} certified meshes: max {max(ratios) if ratios else float('nan'):.3g}")
    if catalog_rows:
        agree = sum(r["agree"] for r in catalog_rows)
        both = sum(r["rd"] == "certified" and r["gf"] == "certified" for r in catalog_rows)
        lines.append(f"- delmesh's default output, --method both: agree on {agree} of {len(catalog_rows)}, "
                     f"both certified on {both}")
    if cost_result:
        lines.append(f"- cost ({cost_result['vertices']} vertices, {cost_result['status']}): certificate / mesh "
                     f"{cost_result['ratio_cert']:.3g}, check process / mesh {cost_result['ratio_wall']:.3g}")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(
        description="Certify CGAL, marching-cubes and delmesh meshes of catalog surfaces with `delmesh check "
                    "--certify --method gradient-flow` (and --method auto), and compare the certified Hausdorff "
                    "bound with a sampled two-sided Hausdorff distance.  Writes <out-dir>/certify_peers.md and "
                    "certify_peers.csv; the module docstring (see the source) defines every column.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--out-dir", default="out/certify_peers", help="output directory (meshes/, checks/, tables)")
    parser.add_argument("--surfaces", default=DEFAULT_SURFACES, help="catalog surfaces, comma separated")
    parser.add_argument("--quick", action="store_true",
                        help="torus and thin_handle only, CGAL sizes 1 and 0.1, marching cubes 16 and 32, delmesh "
                             "without size bound, a coarser Sigma sample (under 2 minutes)")
    parser.add_argument("--delmesh", default=os.path.join(REPO, "build", "delmesh"), help="delmesh binary")
    parser.add_argument("--compare-cgal", default=os.path.join(REPO, "build", "experiments", "compare_cgal"),
                        help="compare_cgal binary")
    parser.add_argument("--cgal-sizes", type=float, nargs="+", default=[1.0, 0.4, 0.2, 0.1, 0.05],
                        help="CGAL facet sizes H (facet distance H/10, bisection error bound 1e-6)")
    parser.add_argument("--cgal-demo-radii", type=float, nargs="+", default=[1.0, 0.5],
                        help="CGAL facet sizes at CGAL's default bisection error bound 1e-3 (distance radius/10)")
    parser.add_argument("--mc-resolutions", type=int, nargs="+", default=[16, 32, 64, 128],
                        help="marching-cubes cells along the box's longest side")
    parser.add_argument("--delmesh-size-bounds", type=float, nargs="*", default=[0.1, 0.05],
                        help="delmesh --size-bound values (a run without size bound is always made)")
    parser.add_argument("--no-cgal", action="store_true", help="skip the CGAL meshes")
    parser.add_argument("--no-seeded-mesh-3", action="store_true",
                        help="skip the Mesh_3 runs with initial points on every component")
    parser.add_argument("--catalog", default="all",
                        help="catalog surfaces whose default delmesh output is checked with --method both "
                             "(comma separated; 'all' for every surface of `delmesh surfaces`, 'none' for none)")
    parser.add_argument("--cost-surface", default="torus", help="surface of the cost measurement ('none': skip it)")
    parser.add_argument("--cost-size-bound", type=float, default=0.02, help="delmesh --size-bound of the cost mesh")
    parser.add_argument("--cost-runs", type=int, default=3, help="runs of each of mesh and certificate")
    parser.add_argument("--timeout", type=float, default=600, help="seconds per delmesh run (mesh or check)")
    parser.add_argument("--sigma-cells", type=int, default=256,
                        help="cells along the box's longest side of the grid whose nodes near Sigma are projected "
                             "onto it (the Sigma sample)")
    parser.add_argument("--max-mesh-samples", type=int, default=2_000_000,
                        help="at most this many barycentric samples per mesh (k is lowered to fit)")
    args = parser.parse_args()
    if args.quick:
        if args.surfaces == DEFAULT_SURFACES:
            args.surfaces = "torus,thin_handle"
        args.cgal_sizes = [1.0, 0.1]
        args.cgal_demo_radii = [1.0]
        args.mc_resolutions = [16, 32]
        args.delmesh_size_bounds = []
        args.sigma_cells = min(args.sigma_cells, 128)
        args.max_mesh_samples = min(args.max_mesh_samples, 300_000)

    out_dir = os.path.abspath(args.out_dir)
    mesh_dir = os.path.join(out_dir, "meshes")
    check_dir = os.path.join(out_dir, "checks")
    os.makedirs(mesh_dir, exist_ok=True)
    os.makedirs(check_dir, exist_ok=True)
    log_file = open(os.path.join(out_dir, "certify_peers.log"), "w")

    def log(text):
        print(text, flush=True)
        log_file.write(text + "\n")
        log_file.flush()

    catalog = {s["name"]: s for s in json.loads(subprocess.run([args.delmesh, "surfaces", "--json"],
                                                               capture_output=True, text=True, check=True).stdout)}
    try:
        revision = subprocess.run(["git", "-C", REPO, "describe", "--always", "--dirty"], capture_output=True,
                                  text=True).stdout.strip()
    except OSError:
        revision = "unknown"
    header = (f"certify_peers git={revision} surfaces={args.surfaces} cgal_sizes={args.cgal_sizes} "
              f"cgal_demo_radii={args.cgal_demo_radii} mc={args.mc_resolutions} "
              f"delmesh_size_bounds={args.delmesh_size_bounds} timeout={args.timeout} sigma_cells={args.sigma_cells}")
    log(header)
    rows = []
    started = time.monotonic()
    for surface in args.surfaces.split(","):
        entry = catalog[surface]
        E = Implicit(entry["equation"], entry["box"])
        expected = entry["genus_per_component"]
        t0 = time.monotonic()
        sigma, spacing = sample_sigma(E, args.sigma_cells)
        sigma_tree = cKDTree(sigma)
        log(f"== {surface}: E = {entry['equation']}, box {entry['box']}, diagonal {E.diagonal:.4g}, gradient by "
            f"{E.gradient_source}; Sigma sample {len(sigma)} points at grid spacing {spacing:.4g} "
            f"({time.monotonic() - t0:.1f} s)")
        meshes = []
        if not args.no_cgal:
            meshes += cgal_meshes(args, surface, mesh_dir, log)
        meshes += mc_meshes(args, surface, E, mesh_dir, log)
        meshes += delmesh_meshes(args, surface, mesh_dir, log)
        for mesher, setting, path in meshes:
            stem = os.path.join(check_dir, os.path.splitext(os.path.basename(path))[0])
            gf, gf_code, gf_wall, gf_command = certify(args.delmesh, path, surface, "gradient-flow", args.timeout,
                                                       stem + ".gradient-flow.json")
            auto, _, auto_wall, _ = certify(args.delmesh, path, surface, "auto", args.timeout, stem + ".auto.json")
            row = {"surface": surface, "mesher": mesher, "setting": setting, "mesh": os.path.relpath(path, out_dir),
                   "expected_genus": json.dumps(expected), "gf_exit": gf_code,
                   "gf_wall_seconds": gf_wall, "auto_wall_seconds": auto_wall,
                   "gf_command": " ".join(gf_command)}
            report = gf if isinstance(gf, dict) else (auto if isinstance(auto, dict) else {})
            row["vertices"] = report.get("vertices")
            row["triangles"] = report.get("triangles")
            genus = report.get("genus_per_component")
            row["genus"] = json.dumps(genus) if genus is not None else "-"
            row["genus_ok"] = genus is not None and sorted(genus) == sorted(expected) and \
                bool(report.get("closed_manifold"))
            row["closed_manifold"] = report.get("closed_manifold")
            row["components"] = report.get("components")
            flow = gf.get("gradient_flow", {}) if isinstance(gf, dict) else {}
            row["gf_verdict"] = flow.get("status") or ("timeout" if gf_code == "timeout" else f"exit {gf_code}")
            row["gf_reason"] = flow.get("reason") or ""
            row["gf_location"] = json.dumps(flow.get("location")) if flow.get("location") else ""
            row["gf_bound"] = flow.get("hausdorff_upper_bound")
            row["gf_bound_relative"] = flow.get("hausdorff_relative")
            row["gf_epsilon"] = flow.get("epsilon")
            row["gf_min_gradient"] = flow.get("min_gradient")
            row["gf_seconds"] = flow.get("seconds")
            topo = auto.get("topology", {}) if isinstance(auto, dict) else {}
            row["auto_verdict"] = topo.get("verdict") or "-"
            row["auto_method"] = topo.get("method") or ""
            row["auto_reason"] = topo.get("reason") or ""
            row["auto_bound"] = topo.get("hausdorff_upper_bound")
            # The sampled two-sided Hausdorff distance.
            vertices, triangles = read_off(path)
            used = np.unique(triangles)
            t1 = time.monotonic()
            m2s, k = mesh_to_surface(E, sigma_tree, spacing, vertices, triangles, args.max_mesh_samples)
            s2m = surface_to_mesh(E, sigma, vertices, triangles)
            sampled = max(m2s, s2m)
            row.update(sampled_mesh_to_surface=m2s, sampled_surface_to_mesh=s2m, sampled_hausdorff=sampled,
                       barycentric_k=k, sigma_samples=len(sigma), sigma_spacing=spacing)
            bound = row["gf_bound"]
            row["ratio"] = bound / sampled if isinstance(bound, (int, float)) and sampled > 0 else None
            flags = []
            certified = row["gf_verdict"] == "certified"
            if certified and not row["genus_ok"]:
                flags.append("UNSOUND: wrong topology certified")
            if certified and isinstance(bound, (int, float)) and bound < sampled - 1e-9 * E.diagonal:
                flags.append("UNSOUND: bound below sampled")
            if topo.get("verdict") == "certified" and not row["genus_ok"]:
                flags.append("UNSOUND: auto certified wrong topology")
            if row["ratio"] is not None and row["ratio"] > 10:
                flags.append("LOOSE")
            row["flags"] = "; ".join(flags)
            rows.append(row)
            log(f"{surface} {mesher} {setting}: {fmt(row['vertices'])} vertices ({len(used)} used), genus "
                f"{row['genus']}{'' if row['genus_ok'] else ' WRONG'}, gradient-flow {row['gf_verdict']}"
                f"{' (' + row['gf_reason'] + ')' if row['gf_reason'] else ''}, bound {fmt(bound)}, sampled "
                f"{fmt(sampled)} (m->S {fmt(m2s)}, S->m {fmt(s2m)}, k={k}, {time.monotonic() - t1:.1f} s), ratio "
                f"{fmt(row['ratio'])}, cert {fmt(row['gf_seconds'])} s / wall {gf_wall:.1f} s, auto "
                f"{row['auto_verdict']} {row['auto_method']} {row['flags']}")
            write_tables(rows, out_dir, header)
    table = write_tables(rows, out_dir, header)
    names = [] if args.catalog == "none" else (list(catalog) if args.catalog == "all" else args.catalog.split(","))
    catalog_text, catalog_rows = catalog_both(args, names, out_dir, log) if names else ("", [])
    cost_text, cost_result = cost(args, out_dir, log) if args.cost_surface != "none" else ("", None)
    sections = [acceptance(rows, catalog_rows, cost_result, catalog), catalog_text, cost_text]
    with open(os.path.join(out_dir, "certify_peers.md"), "a") as f:
        f.write("".join("\n" + text + "\n" for text in sections if text))
    log("")
    log(table)
    for text in sections:
        if text:
            log("")
            log(text)
    log("")
    log(summary(rows))
    log(f"total {time.monotonic() - started:.0f} s; wrote {os.path.join(out_dir, 'certify_peers.md')} and .csv")


if __name__ == "__main__":
    main()
