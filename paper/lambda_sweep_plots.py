#!/usr/bin/env python3
"""Theorem 6.1 against measurement over the λ sweep (experiments/lambda_sweep): the measured
minimum angle, maximum radius-edge ratio and maximum roughness of every surface against the
theorem's bounds arcsin(1/(2+2λ)), 1+λ, 2β(λ); and the size |S| λ² / ∫ dA/lfs², which Theorem
6.1(iii) predicts to stay bounded (O(1/λ²) scaling).  Reads <out>/lambda_sweep.csv only; writes
<out>/figures/lambda_bounds.png and <out>/figures/lambda_size.png."""

import argparse
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from paper_common import loglog_slope, read_csv, save_figure, surface_color  # noqa: E402


def completed(rows):
    return [r for r in rows if str(r["status"]) == "complete" and r["triangles"] > 0]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="out", help="the experiments' output directory")
    args = parser.parse_args()
    meta, rows = read_csv(os.path.join(args.out, "lambda_sweep.csv"))
    rows = completed(rows)
    if not rows:
        raise SystemExit("lambda_sweep.csv has no completed run")
    surfaces = sorted({r["surface"] for r in rows})
    lambdas = sorted({float(r["lambda"]) for r in rows})

    panels = [("min_angle_deg", "bound_min_angle_deg", "minimum angle (deg)", "≥"),
              ("max_radius_edge_ratio", "bound_max_radius_edge_ratio", "max radius-edge ratio", "≤"),
              ("max_roughness_rad", "bound_max_roughness_rad", "max roughness (deg)", "≤")]
    fig, axes = plt.subplots(1, 4, figsize=(17, 4))
    for ax, (measured, bound, label, sense) in zip(axes, panels):
        scale = 180 / math.pi if measured.endswith("_rad") else 1.0
        any_row = {float(r["lambda"]): r[bound] for r in rows}
        ax.plot(lambdas, [any_row[l] * scale for l in lambdas], "k--", marker="_", markersize=22, lw=2,
                label=f"Theorem 6.1 ({sense})")
        for name in surfaces:
            series = sorted((float(r["lambda"]), r[measured] * scale) for r in rows if r["surface"] == name)
            ax.plot([s[0] for s in series], [s[1] for s in series], "o-", color=surface_color(name), label=name)
        ax.set_xlabel("λ")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    # Margins: measured / bound for the two upper bounds (≤ 1 means the bound holds); violations in red.
    ax = axes[3]
    for measured, bound, marker in (("max_radius_edge_ratio", "bound_max_radius_edge_ratio", "s"),
                                    ("max_roughness_rad", "bound_max_roughness_rad", "o")):
        for name in surfaces:
            series = sorted((float(r["lambda"]), r[measured] / r[bound]) for r in rows if r["surface"] == name)
            ax.plot([x for x, _ in series], [y for _, y in series], marker + "-", color=surface_color(name),
                    ms=4, lw=0.8)
            for x, y in series:
                if y > 1:
                    ax.plot([x], [y], "x", color="red", ms=12, mew=2)
                    ax.annotate(f"{name} {y:.3f}", (x, y), textcoords="offset points", xytext=(4, 4),
                                fontsize=7, color="red")
    ax.axhline(1.0, color="k", ls="--", lw=1.5)
    ax.set_xlabel("λ")
    ax.set_ylabel("measured / bound (■ ratio, ● roughness)")
    ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Measured quality vs Theorem 6.1 (git {meta.get('git', '?')})", fontsize=11)
    fig.tight_layout()
    save_figure(fig, args.out, "lambda_bounds.png")

    sized = [r for r in rows if isinstance(r["lfs_integral"], float) and not math.isnan(r["lfs_integral"])]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for name in surfaces:
        series = sorted((1 / float(r["lambda"]), r["vertices"]) for r in rows if r["surface"] == name)
        xs, ys = [s[0] for s in series], [s[1] for s in series]
        label = name if len(xs) < 2 else f"{name} (slope {loglog_slope(xs, ys):.2f})"
        axes[0].loglog(xs, ys, "o-", color=surface_color(name), label=label)
    # Reference slope 2 through the coarsest run of the largest surface.
    biggest = max(surfaces, key=lambda n: max(r["vertices"] for r in rows if r["surface"] == n))
    anchor = min(((1 / float(r["lambda"]), r["vertices"]) for r in rows if r["surface"] == biggest))
    ref = sorted(1 / l for l in lambdas)
    axes[0].loglog(ref, [anchor[1] * (x / anchor[0]) ** 2 for x in ref], "k:", label="∝ 1/λ² (Theorem 6.1(iii))")
    axes[0].set_xlabel("1/λ")
    axes[0].set_ylabel("vertices |S|")
    axes[0].grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    for name in sorted({r["surface"] for r in sized}):
        series = sorted((float(r["lambda"]), r["vertices_lambda2_over_lfs_integral"]) for r in sized
                        if r["surface"] == name)
        axes[1].plot([s[0] for s in series], [s[1] for s in series], "o-", color=surface_color(name), label=name)
    if sized:
        bound = [2 * (2 + 5 * l) ** 2 / math.pi for l in lambdas]
        axes[1].plot(lambdas, bound, "k--", marker="_", markersize=22, label="proof's bound 2(2+5λ)²/π")
        axes[1].set_yscale("log")
    axes[1].set_xlabel("λ")
    axes[1].set_ylabel("|S| λ² / ∫ dA/lfs²")
    axes[1].grid(alpha=0.3)
    axes[1].legend(fontsize=8)
    fig.suptitle("Size: Theorem 6.1(iii)", fontsize=11)
    fig.tight_layout()
    save_figure(fig, args.out, "lambda_size.png")


if __name__ == "__main__":
    main()
