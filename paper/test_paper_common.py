#!/usr/bin/env python3
"""Tests of paper_common.py: the CSV reader with its metadata file, the figure writer (PDF and
PNG), and log axes whose tick labels do not overlap.  Run: /usr/bin/python3 paper/test_paper_common.py
(scripts/test.sh runs it)."""

import json
import os
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_common import plain_number, read_csv, readable_log_ticks, save_figure  # noqa: E402


def tick_label_boxes(fig, axis):
    """The window extents of the visible, non-empty tick labels (major and minor) of an axis."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = []
    for tick in axis.get_major_ticks() + axis.get_minor_ticks():
        label = tick.label1
        if label.get_visible() and label.get_text():
            lo, hi = sorted(axis.get_view_interval())
            if lo <= tick.get_loc() <= hi:
                boxes.append(label.get_window_extent(renderer))
    return boxes


def overlapping(boxes):
    boxes = sorted(boxes, key=lambda b: b.x0)
    return [(a, b) for a, b in zip(boxes, boxes[1:]) if a.overlaps(b)]


def size_panel(inverse_lambdas, readable):
    """The left panel of lambda_size: vertices against 1/λ on log-log axes, 5 inches wide."""
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(inverse_lambdas, [2.0 * x * x for x in inverse_lambdas], "o-")
    if readable:
        readable_log_ticks(ax.xaxis, inverse_lambdas)
        readable_log_ticks(ax.yaxis)
    return fig, ax


class ReadableLogTicks(unittest.TestCase):
    SWEEPS = {"two close λ": [1 / 0.06, 1 / 0.05],
              "the default λ": [1 / l for l in (0.06, 0.05, 0.04, 0.03, 0.02)],
              "many λ": [1 / (0.06 - 0.0025 * k) for k in range(20)],
              "three decades": [1 / l for l in (0.5, 0.1, 0.05, 0.01, 0.005, 0.001)]}

    def test_matplotlib_default_labels_overlap_on_a_narrow_range(self):
        # What the fix is for: without it the 1/λ axis of two close λ has overlapping labels.
        fig, ax = size_panel(self.SWEEPS["two close λ"], readable=False)
        self.assertTrue(overlapping(tick_label_boxes(fig, ax.xaxis)))
        plt.close(fig)

    def test_labels_never_overlap_and_at_least_two_show(self):
        for name, xs in self.SWEEPS.items():
            with self.subTest(sweep=name):
                fig, ax = size_panel(xs, readable=True)
                for axis in (ax.xaxis, ax.yaxis):
                    boxes = tick_label_boxes(fig, axis)
                    self.assertGreaterEqual(len(boxes), 2, name)
                    if axis is ax.xaxis:
                        self.assertEqual(overlapping(boxes), [], name)
                    else:  # vertical axis: compare the boxes' heights
                        ys = sorted(boxes, key=lambda b: b.y0)
                        self.assertFalse(any(a.y1 > b.y0 for a, b in zip(ys, ys[1:])), name)
                plt.close(fig)

    def test_the_sweep_values_are_the_ticks_and_the_extremes_stay(self):
        xs = self.SWEEPS["the default λ"]
        fig, ax = size_panel(xs, readable=True)
        fig.canvas.draw()
        labels = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
        self.assertEqual(labels, ["16.7", "20", "25", "33.3", "50"])
        plt.close(fig)

    def test_plain_numbers(self):
        self.assertEqual([plain_number(v) for v in (2000, 0.0118, 1 / 0.06, 1e-5, 5e7)],
                         ["2000", "0.0118", "16.7", "1e-05", "5e+07"])


class CsvAndFigures(unittest.TestCase):
    def test_read_csv_takes_the_header_line_and_the_metadata_file(self):
        with tempfile.TemporaryDirectory() as out:
            path = os.path.join(out, "runs.csv")
            with open(path, "w") as f:
                f.write("surface,lambda,vertices\nsphere,0.06,25\n")
            with open(path + ".json", "w") as f:
                json.dump({"program": "lambda_sweep", "git": "abc", "parameters": {"seed": "1", "git": "x"}}, f)
            meta, rows = read_csv(path)
            self.assertEqual(rows, [{"surface": "sphere", "lambda": 0.06, "vertices": 25}])
            self.assertEqual((meta["program"], meta["git"], meta["seed"]), ("lambda_sweep", "abc", "1"))
            with open(path, "w") as f:
                f.write("# program=lambda_sweep git=abc\nsurface,lambda\n")
            with self.assertRaises(ValueError):
                read_csv(path)

    def test_every_figure_is_written_as_pdf_and_png(self):
        with tempfile.TemporaryDirectory() as out:
            fig, ax = plt.subplots()
            ax.plot([1, 2], [3, 4])
            targets = save_figure(fig, out, "example")
            plt.close(fig)
            self.assertEqual([os.path.basename(t) for t in targets], ["example.pdf", "example.png"])
            with open(targets[0], "rb") as f:
                self.assertEqual(f.read(5), b"%PDF-")
            with open(targets[1], "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
