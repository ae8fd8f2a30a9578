"""Tests of the Python module delmesh against known answers and against the program `delmesh`.

Run by ctest (entry `python`, fast tier) with PYTHONPATH=<build>/python and DELMESH_BINARY set to
the program of the same build; by hand:
    PYTHONPATH=build/python DELMESH_BINARY=build/delmesh python3 -m unittest discover -s python/tests
"""

import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np

import delmesh

DELMESH_BINARY = os.environ.get("DELMESH_BINARY", "delmesh")


def run_cli(*args):
    """Runs the program; returns (exit code, stdout, stderr)."""
    p = subprocess.run([DELMESH_BINARY, *args], capture_output=True, text=True, check=False)
    return p.returncode, p.stdout, p.stderr


def cli_error(*args):
    """The message of the program's single `error:` line for args (which must be refused)."""
    code, _, err = run_cli(*args)
    assert code == 2, (args, code, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    return lines[0][len("error: "):]


def python_terms(message):
    """The program's message as the module words it: each flag --some-option becomes the
    argument some_option (--lambda becomes lam)."""
    def name(m):
        return "lam" if m.group(1) == "lambda" else m.group(1).replace("-", "_")
    return re.sub(r"--([a-z][a-z0-9]*(?:-[a-z0-9]+)*)", name, message)


def read_off(path):
    """Vertices (float64) and triangles (int64) of an ASCII OFF file as the program writes it."""
    with open(path) as f:
        words = f.read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    at = 4
    vertices = np.array(words[at:at + 3 * nv], dtype=np.float64).reshape(nv, 3)
    at += 3 * nv
    faces = np.array(words[at:at + 4 * nf], dtype=np.int64).reshape(nf, 4)
    assert (faces[:, 0] == 3).all()
    return vertices, faces[:, 1:]


def without_timings(value):
    """The statistics without what differs from run to run (seconds, the program's peak memory) or
    between the program and the module by design (mesh_file)."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items()
                if not k.startswith("seconds") and k not in ("mesh_file", "peak_memory_bytes")}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


class SurfacesTest(unittest.TestCase):
    def test_catalog_is_the_programs(self):
        code, out, _ = run_cli("surfaces", "--json")
        self.assertEqual(code, 0)
        surfaces = delmesh.surfaces()
        self.assertEqual(surfaces, json.loads(out))
        torus = next(s for s in surfaces if s["name"] == "torus")
        self.assertEqual(torus["genus_per_component"], [1])
        self.assertEqual(len(torus["box"]), 6)


class MeshTest(unittest.TestCase):
    def test_shapes_dtypes_and_statistics(self):
        result = delmesh.mesh(surface="sphere")
        self.assertEqual(result.status, "complete")
        self.assertEqual(result.vertices.dtype, np.float64)
        self.assertEqual(result.triangles.dtype, np.int64)
        self.assertEqual(result.vertices.ndim, 2)
        self.assertEqual(result.vertices.shape[1], 3)
        self.assertEqual(result.triangles.shape[1], 3)
        self.assertGreater(len(result.triangles), 0)
        self.assertEqual(result.stats["status"], "complete")
        self.assertEqual(result.stats["vertices"], len(result.vertices))
        self.assertEqual(result.stats["triangles"], len(result.triangles))
        self.assertEqual(result.stats["seed"], 1)
        self.assertEqual(result.stats["surface"]["name"], "sphere")
        self.assertNotIn("mesh_file", result.stats)
        self.assertTrue(result.triangles.min() >= 0 and result.triangles.max() < len(result.vertices))
        # A closed 2-manifold: Euler's formula with 3F = 2E.
        v, f = len(result.vertices), len(result.triangles)
        self.assertEqual(v - f // 2, 2)
        # On the unit sphere (E = x^2+y^2+z^2-1): every vertex is a sample of the surface.
        np.testing.assert_allclose(np.linalg.norm(result.vertices, axis=1), 1.0, rtol=0, atol=1e-9)

    def test_torus_has_genus_one_by_the_checker(self):
        result = delmesh.mesh(surface="torus")
        self.assertEqual(result.status, "complete")
        report = delmesh.check(result.vertices, result.triangles, lam=0.06)
        self.assertEqual(report["components"], 1)
        self.assertEqual(report["genus_per_component"], [1])
        self.assertEqual(report["euler_characteristic"], 0)
        self.assertTrue(report["closed_manifold"])
        self.assertTrue(report["oriented"])
        self.assertTrue(report["pass"]["all"])
        self.assertEqual(report["min_angle_deg"], result.stats["min_angle_deg"])

    def test_same_mesh_and_statistics_as_the_program(self):
        cases = [
            (["--surface", "torus", "--seed", "7"], dict(surface="torus", seed=7)),
            (["--expr", "x^2+2*y^2+3*z^2-1", "--box", "-2,2,-2,2,-2,2", "--phase", "topology", "--lambda", "0.05"],
             dict(expr="x^2+2*y^2+3*z^2-1", box=(-2, 2, -2, 2, -2, 2), phase="topology", lam=0.05)),
        ]
        with tempfile.TemporaryDirectory() as d:
            for args, kwargs in cases:
                with self.subTest(args=args):
                    off, stats = os.path.join(d, "m.off"), os.path.join(d, "m.json")
                    code, _, err = run_cli("mesh", *args, "--out", off, "--stats", stats, "--quiet")
                    self.assertEqual(code, 0, err)
                    vertices, triangles = read_off(off)
                    with open(stats) as f:
                        cli_stats = json.load(f)
                    result = delmesh.mesh(**kwargs)
                    np.testing.assert_array_equal(result.vertices, vertices)  # exactly: 17 digits in the file
                    np.testing.assert_array_equal(result.triangles, triangles)
                    self.assertEqual(without_timings(result.stats), without_timings(cli_stats))

    def test_input_mesh_is_remeshed_as_by_the_program(self):
        # A torus of 48 x 12 quadrilaterals: triangulated, then remeshed above the default floor.
        n, m = 48, 12
        lines = ["OFF", f"{n * m} {n * m} 0"]
        for i in range(n):
            for j in range(m):
                u, v = 2 * np.pi * i / n, 2 * np.pi * j / m
                rho = 1 + 0.4 * np.cos(v)
                lines.append(f"{rho * np.cos(u)!r} {rho * np.sin(u)!r} {0.4 * np.sin(v)!r}")
        for i in range(n):
            for j in range(m):
                a, b = i * m + j, (i + 1) % n * m + j
                lines.append(f"4 {a} {b} {(i + 1) % n * m + (j + 1) % m} {i * m + (j + 1) % m}")
        with tempfile.TemporaryDirectory() as d:
            quads, off, stats = (os.path.join(d, name) for name in ("quads.off", "m.off", "m.json"))
            with open(quads, "w") as f:
                f.write("\n".join(lines) + "\n")
            code, _, err = run_cli("mesh", "--input-mesh", quads, "--out", off, "--stats", stats, "--quiet")
            self.assertEqual(code, 0, err)
            vertices, triangles = read_off(off)
            with open(stats) as f:
                cli_stats = json.load(f)
            result = delmesh.mesh(input_mesh=quads)
        self.assertEqual(result.status, "complete")
        self.assertEqual(result.stats["input_mesh"]["polygons_triangulated"], n * m)
        self.assertEqual(delmesh.check(result.vertices, result.triangles)["genus_per_component"], [1])
        np.testing.assert_array_equal(result.vertices, vertices)
        np.testing.assert_array_equal(result.triangles, triangles)
        self.assertEqual(without_timings(result.stats), without_timings(cli_stats))

    def test_point_limit_returns_the_partial_mesh_with_its_status(self):
        result = delmesh.mesh(surface="torus", max_points=20)
        self.assertEqual(result.status, "point_limit")
        self.assertEqual(result.stats["status"], "point_limit")
        self.assertEqual(result.stats["vertices"], len(result.vertices))

    def test_invalid_input_raises_the_programs_message(self):
        box = "-1,1,-1,1,-1,1"
        cases = [
            (dict(expr="x^2+", box=box), ["--expr", "x^2+", "--box", box]),
            (dict(expr="x^2+y^2+z^2-1"), ["--expr", "x^2+y^2+z^2-1"]),
            (dict(surface="no_such_surface"), ["--surface", "no_such_surface"]),
            (dict(surface="sphere", expr="x"), ["--surface", "sphere", "--expr", "x"]),
            (dict(), []),
            (dict(surface="sphere", lam=0.5), ["--surface", "sphere", "--lambda", "0.5"]),
            (dict(surface="sphere", lam=float("nan")), ["--surface", "sphere", "--lambda", "nan"]),
            (dict(surface="sphere", max_points=0), ["--surface", "sphere", "--max-points", "0"]),
            (dict(surface="sphere", seed=-1), ["--surface", "sphere", "--seed", "-1"]),
            (dict(surface="sphere", threads=2000), ["--surface", "sphere", "--threads", "2000"]),
            (dict(surface="sphere", time_limit=-1), ["--surface", "sphere", "--time-limit", "-1"]),
            (dict(surface="sphere", phase="some"), ["--surface", "sphere", "--phase", "some"]),
            (dict(surface="sphere", box="0,1,0,1"), ["--surface", "sphere", "--box", "0,1,0,1"]),
            (dict(expr="x^2+y^2+z^2-4", box=box), ["--expr", "x^2+y^2+z^2-4", "--box", box]),
            (dict(input_mesh="/nonexistent/m.off"), ["--input-mesh", "/nonexistent/m.off"]),
        ]
        with tempfile.TemporaryDirectory() as d:
            for kwargs, args in cases:
                with self.subTest(kwargs=kwargs):
                    message = cli_error("mesh", *args, "--out", os.path.join(d, "m.off"),
                                        "--stats", os.path.join(d, "m.json"), "--quiet")
                    with self.assertRaises(ValueError) as caught:
                        delmesh.mesh(**kwargs)
                    self.assertEqual(str(caught.exception), python_terms(message))
                    self.assertNotIn("--", str(caught.exception))

    def test_expr_must_be_text(self):
        with self.assertRaisesRegex(TypeError, "not a Python function"):
            delmesh.mesh(expr=lambda x, y, z: x * x + y * y + z * z - 1, box="-2,2,-2,2,-2,2")
        with self.assertRaisesRegex(TypeError, "not int"):
            delmesh.mesh(expr=1, box="-2,2,-2,2,-2,2")

    def test_input_mesh_as_arrays_is_remeshed_as_the_file(self):
        sphere = delmesh.mesh(surface="sphere", size_bound=0.5)
        from_arrays = delmesh.mesh(input_mesh=(sphere.vertices, sphere.triangles))
        self.assertEqual(from_arrays.stats["input_mesh"]["file"], "input_mesh")
        self.assertEqual(from_arrays.stats["input_mesh"]["vertices"], len(sphere.vertices))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "s.off")
            delmesh.save(path, sphere.vertices, sphere.triangles)
            from_file = delmesh.mesh(input_mesh=path)
        np.testing.assert_array_equal(from_arrays.vertices, from_file.vertices)
        np.testing.assert_array_equal(from_arrays.triangles, from_file.triangles)
        with self.assertRaisesRegex(ValueError, "input_mesh"):
            delmesh.mesh(input_mesh=(sphere.vertices,))

    def test_save_writes_what_the_program_reads(self):
        torus = delmesh.mesh(surface="torus")
        with tempfile.TemporaryDirectory() as d:
            for ext in ("off", "ply", "obj"):
                path = os.path.join(d, "t." + ext)
                delmesh.save(path, torus.vertices, torus.triangles)
                code, out, err = run_cli("check", path, "--json")
                self.assertEqual(code, 0, err)
                report = json.loads(out)
                self.assertEqual(report["vertices"], len(torus.vertices))
                self.assertEqual(report["genus_per_component"], [1])
            with self.assertRaisesRegex(ValueError, "extension"):
                delmesh.save(os.path.join(d, "t.xyz"), torus.vertices, torus.triangles)
            with self.assertRaisesRegex(ValueError, "triangles"):
                delmesh.save(os.path.join(d, "u.off"), torus.vertices, torus.triangles[:, :2])

    def test_certify_gives_the_certificates_of_certify(self):
        result = delmesh.mesh(surface="torus", certify=True)
        expected = delmesh.certify(result.vertices, result.triangles, surface="torus")
        self.assertEqual(result.stats["certificate"]["topology"], expected["topology"])
        self.assertEqual(result.stats["certificate"]["topology"]["verdict"], "certified")
        self.assertIsNone(delmesh.mesh(surface="torus", certify=True, max_points=20).stats["certificate"])
        sphere = delmesh.mesh(surface="sphere")
        with self.assertRaisesRegex(ValueError, "certify needs expr or surface"):
            delmesh.mesh(input_mesh=(sphere.vertices, sphere.triangles), certify=True)

    def test_max_distance_is_certified(self):
        result = delmesh.mesh(surface="sphere", max_distance=0.01)
        self.assertEqual(result.status, "complete")
        self.assertEqual(result.stats["distance"]["status"], "certified")
        self.assertLessEqual(result.stats["distance"]["hausdorff_upper_bound"], 0.01)

    def test_lambda_beyond_the_theorem_warns(self):
        with self.assertWarnsRegex(RuntimeWarning, "Theorem 6.1 does not cover"):
            result = delmesh.mesh(surface="sphere", lam=0.1)
        self.assertEqual(result.stats["lambda"], 0.1)


class ThreadsTest(unittest.TestCase):
    def test_the_gil_is_released_while_meshing(self):
        ticks = []
        stop = threading.Event()

        def tick():
            while not stop.is_set():
                ticks.append(time.monotonic())
                time.sleep(0.005)

        ticker = threading.Thread(target=tick)
        ticker.start()
        try:
            time.sleep(0.05)
            start = time.monotonic()
            # A run of about a second (4368 vertices), long enough to count the ticks.
            result = delmesh.mesh(surface="torus", size_bound=0.05)
            end = time.monotonic()
        finally:
            stop.set()
            ticker.join()
        self.assertEqual(result.status, "complete")
        during = [t for t in ticks if start < t < end]
        # A thread blocked on the GIL would not tick at all during the call; with the GIL released
        # it ticks about every 5 ms (at least a third of that rate is required).
        self.assertGreater(end - start, 0.1)
        self.assertGreaterEqual(len(during), (end - start) / 0.005 / 3)

    def test_ctrl_c_stops_the_run_and_raises_keyboard_interrupt(self):
        # SIGINT comes from another thread once the refinement reports progress, so the main
        # thread receives it while it waits inside mesh(), not while it runs Python code.
        lines = []
        refining, finished = threading.Event(), threading.Event()
        sent = []

        def progress(line):
            lines.append(line)
            refining.set()

        def interrupt():
            if refining.wait(timeout=60) and not finished.is_set():
                sent.append(time.monotonic())
                os.kill(os.getpid(), signal.SIGINT)

        sender = threading.Thread(target=interrupt)
        sender.start()
        try:
            with self.assertRaises(KeyboardInterrupt) as caught:
                # A run of several seconds (about 27 000 vertices), so that it is still running
                # when the first progress report (after 0.5 s) sends the signal.
                delmesh.mesh(surface="torus", size_bound=0.02, progress=progress)
            stopped = time.monotonic()
        finally:
            finished.set()
            refining.set()
            sender.join()
        self.assertTrue(sent, "the run ended before its first progress report")
        self.assertIsInstance(lines[0], delmesh.ProgressReport)
        self.assertIn("points", str(lines[0]))
        self.assertLess(stopped - sent[0], 2.0)
        # The exception carries the partial mesh, as the program writes it.
        partial = caught.exception.partial
        self.assertEqual(partial.status, "interrupted")
        self.assertEqual(partial.stats["status"], "interrupted")
        self.assertEqual(partial.stats["vertices"], len(partial.vertices))
        self.assertGreater(len(partial.triangles), 0)
        # The library is usable again: the worker was joined and the lock released.
        self.assertEqual(delmesh.mesh(surface="sphere").status, "complete")

    def test_a_time_limit_passing_while_compiling_raises_timeout_error(self):
        # A sphere times 40 factors (2 + sin(x + i)): compiling its systems takes several
        # seconds; the limit counts from the call and stops the compilation between its steps.
        expr = "".join("(2+sin(x+%d))*" % i for i in range(1, 41)) + "(x^2+y^2+z^2-1)"
        start = time.monotonic()
        with self.assertRaises(TimeoutError) as raised:
            delmesh.mesh(expr=expr, box="-2,2,-2,2,-2,2", time_limit=0.5)
        self.assertLess(time.monotonic() - start, 0.5 + 2.0)
        self.assertIn("stopped by the time limit while", str(raised.exception))
        # The library is usable again.
        self.assertEqual(delmesh.mesh(surface="sphere").status, "complete")

    def test_an_exception_in_progress_stops_the_run(self):
        def progress(line):
            raise RuntimeError("enough")

        with self.assertRaisesRegex(RuntimeError, "enough"):
            # Long enough to report progress (after 0.5 s) before it ends.
            delmesh.mesh(surface="torus", size_bound=0.02, progress=progress)


class FakeBar:
    """What a tqdm-style progress callback uses of a bar: n, total, set_description, refresh."""

    def __init__(self):
        self.n = 0
        self.total = None
        self.descriptions = []
        self.counts = []

    def set_description(self, text):
        self.descriptions.append(text)

    def refresh(self):
        self.counts.append(self.n)


class ProgressTest(unittest.TestCase):
    # A torus run of one to two seconds: refinement reports (every 0.5 s), then the one
    # of the distance certificate.
    RUN = dict(surface="torus", size_bound=0.03)

    def test_the_callback_gets_reports_with_attributes(self):
        reports = []
        result = delmesh.mesh(progress=reports.append, **self.RUN)
        self.assertEqual(result.status, "complete")
        self.assertGreaterEqual(len(reports), 2)
        phases = ["topology", "geometry", "certifying"]
        for before, report in zip([None] + reports, reports):
            self.assertIsInstance(report, delmesh.ProgressReport)
            self.assertIn(report.phase, phases)
            self.assertIsInstance(report.points, int)
            self.assertIsInstance(report.elapsed, float)
            self.assertIsInstance(report.queued, dict)
            # A callback that prints its argument prints the text line.
            self.assertEqual(str(report), report.text)
            self.assertEqual("%s" % report, report.text)
            self.assertGreater(report.points, 0)
            self.assertLessEqual(report.elapsed, result.stats["seconds"])
            if before is not None:
                self.assertGreaterEqual(phases.index(report.phase), phases.index(before.phase))
                self.assertGreaterEqual(report.points, before.points)
                self.assertGreaterEqual(report.elapsed, before.elapsed)
            if report.phase == "certifying":
                self.assertEqual(report.queued, {})
                self.assertEqual(report.text, "certifying the distance to the surface (gradient flow)")
            else:
                self.assertTrue(report.queued)
                self.assertTrue(all(isinstance(v, int) for v in report.queued.values()))
                self.assertTrue(report.text.startswith("%s: points %d, queued" % (report.phase, report.points)))
        self.assertIn("geometry", [r.phase for r in reports])
        self.assertEqual(reports[-1].phase, "certifying")
        self.assertEqual(reports[-1].points, result.stats["points"])

    def test_a_tqdm_style_bar_follows_the_points(self):
        # The pattern of docs/python.md, with a stand-in for tqdm.tqdm.
        bar = FakeBar()

        def progress(report):
            bar.n = report.points
            bar.set_description(report.phase)
            bar.refresh()

        result = delmesh.mesh(progress=progress, **self.RUN)
        self.assertEqual(bar.counts, sorted(bar.counts))
        self.assertEqual(bar.n, result.stats["points"])
        self.assertEqual(bar.descriptions[-1], "certifying")
        self.assertIn("geometry", bar.descriptions)


class CheckTest(unittest.TestCase):
    TETRAHEDRON = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64),
                   np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))

    def test_closed_and_open_meshes(self):
        report = delmesh.check(*self.TETRAHEDRON)
        self.assertEqual(report["vertices"], 4)
        self.assertEqual(report["edges"], 6)
        self.assertEqual(report["euler_characteristic"], 2)
        self.assertEqual(report["genus_per_component"], [0])
        self.assertTrue(report["closed"])
        self.assertNotIn("pass", report)
        vertices, triangles = self.TETRAHEDRON
        report = delmesh.check(vertices.tolist(), triangles[:3].tolist())  # plain lists work too
        self.assertFalse(report["closed"])
        self.assertEqual(report["boundary_edges"], 3)
        self.assertEqual(report["boundary_loops"], 1)
        self.assertEqual(report["genus_per_component"], [None])

    def test_same_report_as_the_program(self):
        result = delmesh.mesh(surface="two_blobs", phase="topology")
        with tempfile.TemporaryDirectory() as d:
            off = os.path.join(d, "m.off")
            code, _, err = run_cli("mesh", "--surface", "two_blobs", "--phase", "topology", "--out", off,
                                   "--stats", os.path.join(d, "m.json"), "--quiet")
            self.assertEqual(code, 0, err)
            code, out, _ = run_cli("check", off, "--lambda", "0.06", "--json")
        self.assertEqual(delmesh.check(result.vertices, result.triangles, lam=0.06), json.loads(out))

    def test_invalid_input(self):
        vertices, triangles = self.TETRAHEDRON
        with self.assertRaisesRegex(ValueError, "vertex index 4 but there are 4 points"):
            delmesh.check(vertices, triangles + 1)
        with self.assertRaisesRegex(ValueError, "negative index"):
            delmesh.check(vertices, triangles - 1)
        with self.assertRaisesRegex(ValueError, "N x 3"):
            delmesh.check(vertices[:, :2], triangles)
        with self.assertRaisesRegex(ValueError, "integer"):
            delmesh.check(vertices, triangles.astype(np.float64))
        with tempfile.TemporaryDirectory() as d:
            off = os.path.join(d, "t.off")
            with open(off, "w") as f:
                f.write("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
            message = cli_error("check", off, "--lambda", "0.2")
        with self.assertRaises(ValueError) as caught:
            delmesh.check(vertices, triangles, lam=0.2)
        self.assertEqual(str(caught.exception), python_terms(message))


class CertifyTest(unittest.TestCase):
    def test_same_certificates_as_the_program(self):
        result = delmesh.mesh(surface="torus", size_bound=0.1)
        certificates = delmesh.certify(result.vertices, result.triangles, surface="torus", method="both")
        self.assertEqual(certificates["topology"]["verdict"], "certified")
        self.assertEqual(certificates["topology"]["method"], "both")
        bound = certificates["topology"]["hausdorff_upper_bound"]
        self.assertGreater(bound, 0)
        self.assertEqual(len(certificates["gradient_flow"]["triangle_distance_bounds"]), len(result.triangles))
        with tempfile.TemporaryDirectory() as d:
            off = os.path.join(d, "t.off")
            code, _, err = run_cli("mesh", "--surface", "torus", "--size-bound", "0.1", "--out", off,
                                   "--stats", os.path.join(d, "t.json"), "--quiet")
            self.assertEqual(code, 0, err)
            code, out, err = run_cli("check", off, "--surface", "torus", "--certify", "--method",
                                     "gradient-flow", "--json")
            self.assertEqual(code, 0, err)
        program = json.loads(out)
        flow = delmesh.certify(result.vertices, result.triangles, surface="torus", method="gradient-flow")
        self.assertEqual(flow["topology"], program["topology"])
        self.assertEqual(flow["gradient_flow"]["hausdorff_upper_bound"], bound)
        self.assertNotIn("certificate", flow)

    def test_a_squashed_mesh_is_not_certified_and_bad_input_raises(self):
        result = delmesh.mesh(surface="sphere")
        squashed = result.vertices * np.array([1.0, 1.0, 0.3])
        certificates = delmesh.certify(squashed, result.triangles, surface="sphere", method="gradient-flow")
        self.assertNotEqual(certificates["topology"]["verdict"], "certified")
        self.assertIsNone(certificates["topology"]["hausdorff_upper_bound"])
        with self.assertRaisesRegex(ValueError, "method: expected auto"):
            delmesh.certify(result.vertices, result.triangles, surface="sphere", method="flow")
        with self.assertRaisesRegex(ValueError, "negative index"):
            delmesh.certify(result.vertices, result.triangles - 1, surface="sphere")


class SolveTest(unittest.TestCase):
    def test_critical_points_of_the_torus_along_x(self):
        # The catalog torus (x^2+y^2+z^2+R^2-r^2)^2 - 4R^2(x^2+y^2), R = 1, r = 0.4, revolves about z:
        # the height along x has exactly four critical points on it, (±(R+r), 0, 0) and (±(R-r), 0, 0).
        result = delmesh.solve("surface_critical", surface="torus", direction=(1, 0, 0))
        self.assertEqual(result.status, "complete")
        np.testing.assert_allclose(sorted(result.roots[:, 0]), [-1.4, -0.6, 0.6, 1.4], rtol=0, atol=1e-12)
        np.testing.assert_allclose(result.roots[:, 1:], 0, rtol=0, atol=1e-12)
        self.assertEqual(result.undecided.shape, (0, 3, 2))
        code, out, err = run_cli("solve", "--surface", "torus", "--primitive", "surface_critical",
                                 "--direction", "1,0,0", "--json")
        self.assertEqual(code, 0, err)
        cli = json.loads(out)
        self.assertEqual(result.status, cli["status"])
        np.testing.assert_array_equal(result.roots, np.array(cli["roots"], dtype=np.float64).reshape(-1, 3))
        self.assertEqual(result.boxes, cli["boxes"])

    def test_line_roots_on_the_unit_sphere(self):
        result = delmesh.solve("surface_line", expr="x^2+y^2+z^2-1", box="-2,2,-2,2,-2,2",
                               point=(0, 0, 0), direction="0,0,1")
        self.assertEqual(result.status, "complete")
        self.assertEqual(result.solver, "univariate isolator")
        np.testing.assert_allclose(sorted(result.roots[:, 2]), [-1.0, 1.0], rtol=0, atol=1e-12)

    def test_invalid_input_raises_the_programs_message(self):
        cases = [
            (dict(primitive="no_such_primitive", surface="torus"), ["--primitive", "no_such_primitive"]),
            (dict(primitive="surface_line", surface="torus", point=(1, 2, 3)),
             ["--primitive", "surface_line", "--point", "1,2,3"]),
            (dict(primitive="surface_line", surface="torus", point="1,2", direction=(0, 0, 1)),
             ["--primitive", "surface_line", "--point", "1,2", "--direction", "0,0,1"]),
            (dict(primitive="surface_critical", surface="torus", point=(0, 0, 0)),
             ["--primitive", "surface_critical", "--point", "0,0,0"]),
            (dict(primitive="surface_critical", surface="torus", max_boxes=0),
             ["--primitive", "surface_critical", "--max-boxes", "0"]),
        ]
        for kwargs, args in cases:
            with self.subTest(kwargs=kwargs):
                message = cli_error("solve", "--surface", "torus", *args)
                with self.assertRaises(ValueError) as caught:
                    delmesh.solve(**kwargs)
                self.assertEqual(str(caught.exception), python_terms(message))


CHECKED = "<!-- output checked by python/tests/test_delmesh.py -->"


def checked_blocks(text):
    """The fenced blocks of a Markdown text that follow a line CHECKED, as (language, lines, the
    lines of the next fenced block)."""
    lines = text.split("\n")

    def fence(start):
        begin = next(i for i in range(start, len(lines)) if lines[i].startswith("```"))
        end = next(i for i in range(begin + 1, len(lines)) if lines[i].startswith("```"))
        return lines[begin][3:].strip(), lines[begin + 1:end], end + 1

    blocks = []
    for i, line in enumerate(lines):
        if line.strip() == CHECKED:
            language, body, after = fence(i + 1)
            blocks.append((language, body, fence(after)[1] if language == "python" else None))
    return blocks


def output_matches(expected, found):
    """Whether the lines found match the lines expected, where a line '...' stands for any number
    of lines and '…' within a line for any text."""
    def line(e, f):
        return re.fullmatch(".*".join(re.escape(part) for part in e.split("…")), f) is not None

    def match(i, j):
        if i == len(expected):
            return j == len(found)
        if expected[i] == "...":
            return any(match(i + 1, k) for k in range(j, len(found) + 1))
        return j < len(found) and line(expected[i], found[j]) and match(i + 1, j + 1)
    return match(0, 0)


def uv_sphere_off(rings, sectors):
    """The latitude-longitude sphere of tests/apps/check_command_test.cpp, as the same OFF text."""
    vertices = ["0 0 1"]
    for i in range(1, rings):
        for j in range(sectors):
            theta, phi = math.pi * i / rings, 2 * math.pi * j / sectors
            vertices.append("%.17g %.17g %.17g" % (math.sin(theta) * math.cos(phi),
                                                    math.sin(theta) * math.sin(phi), math.cos(theta)))
    vertices.append("0 0 -1")
    south = 1 + (rings - 1) * sectors

    def at(i, j):
        return 1 + (i - 1) * sectors + j % sectors
    faces = [f"3 0 {at(1, j)} {at(1, j + 1)}" for j in range(sectors)]
    for i in range(1, rings - 1):
        for j in range(sectors):
            faces += [f"3 {at(i, j)} {at(i + 1, j)} {at(i, j + 1)}",
                      f"3 {at(i, j + 1)} {at(i + 1, j)} {at(i + 1, j + 1)}"]
    faces += [f"3 {south} {at(rings - 1, j + 1)} {at(rings - 1, j)}" for j in range(sectors)]
    return f"OFF\n{south + 1} {len(faces)} 0\n" + "\n".join(vertices + faces) + "\n"


class ExampleTest(unittest.TestCase):
    """The examples of README.md and docs/*.md: python/example.py is shown verbatim, and every
    block marked CHECKED prints what it shows."""
    SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    BUILD = os.path.dirname(os.path.abspath(DELMESH_BINARY))
    DOCUMENTS = ["README.md"] + sorted(os.path.join("docs", name) for name in os.listdir(
        os.path.join(SOURCE, "docs")) if name.endswith(".md"))

    # The subprocesses import the module this test imported, whatever their directory.
    ENVIRONMENT = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.abspath(delmesh.__file__)))

    def read(self, document):
        with open(os.path.join(self.SOURCE, document)) as f:
            return f.read()

    def command(self, line):
        """A documented command line, with build/, python3 and python/ resolved for this build."""
        line = re.sub(r"^(PYTHONPATH=build/python )?python3 ", lambda m: sys.executable + " ", line)
        line = line.replace("python/example.py", os.path.join(self.SOURCE, "python", "example.py"))
        return re.sub(r"(?<![\w/.])build/", self.BUILD + "/", line)

    def run_session(self, lines, directory):
        """Runs each '$ ' line of a block in directory; compares stdout with the lines after it."""
        while lines:
            self.assertTrue(lines[0].startswith("$ "), lines[0])
            end = next((k for k in range(1, len(lines)) if lines[k].startswith("$ ")), len(lines))
            command, expected = lines[0][2:], lines[1:end]
            if expected and expected[-1] == "drew ./torus.png" and not has_matplotlib():
                expected = expected[:-1] + ["matplotlib is not installed: no picture"]
            p = subprocess.run(["bash", "-o", "pipefail", "-c", self.command(command)], cwd=directory,
                               env=self.ENVIRONMENT, capture_output=True, text=True, check=False)
            self.assertEqual(p.returncode, 0, f"{command}\n{p.stderr}")
            found = p.stdout.rstrip("\n").split("\n") if p.stdout else []
            self.assertTrue(output_matches(expected, found),
                            f"{command}\nshows:\n" + "\n".join(expected) + "\nprints:\n" + p.stdout)
            lines = lines[end:]

    def test_the_documented_outputs_are_printed(self):
        counts = {}
        for document in self.DOCUMENTS:
            for language, body, output in checked_blocks(self.read(document)):
                counts[document] = counts.get(document, 0) + 1
                with self.subTest(document=document, block=body[0]), tempfile.TemporaryDirectory() as d:
                    with open(os.path.join(d, "uv_sphere.off"), "w") as f:
                        f.write(uv_sphere_off(8, 16))
                    if language == "python":
                        p = subprocess.run([sys.executable, "-c", "\n".join(body)], cwd=d,
                                           env=self.ENVIRONMENT, capture_output=True, text=True,
                                           check=False)
                        self.assertEqual(p.returncode, 0, p.stderr)
                        self.assertTrue(output_matches(output, p.stdout.rstrip("\n").split("\n")),
                                        "shows:\n" + "\n".join(output) + "\nprints:\n" + p.stdout)
                    else:
                        self.run_session(body, d)
        # The blocks the documents mark: a missing marker must not pass silently.
        self.assertEqual(counts, {"README.md": 2, "docs/certificates.md": 1, "docs/cli.md": 2,
                                  "docs/extending.md": 2, "docs/python.md": 1})

    def test_the_python_example_is_shown_and_its_mesh_checks(self):
        example = os.path.join(self.SOURCE, "python", "example.py")
        with open(example) as f:
            self.assertIn(f.read(), self.read(os.path.join("docs", "python.md")),
                          "docs/python.md shows python/example.py verbatim")
        with tempfile.TemporaryDirectory() as d:
            p = subprocess.run([sys.executable, example, d], capture_output=True, text=True, check=False)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("genus per component: [1] closed manifold: True", p.stdout)
            code, out, err = run_cli("check", os.path.join(d, "torus.off"), "--lambda", "0.06", "--json")
            self.assertEqual(code, 0, err)
            report = json.loads(out)
        self.assertEqual(report["genus_per_component"], [1])
        self.assertTrue(report["pass"]["all"])


def has_matplotlib():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


if __name__ == "__main__":
    unittest.main()
