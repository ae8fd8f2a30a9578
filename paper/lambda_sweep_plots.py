#!/usr/bin/env python3
"""Theorem 6.1 against measurement over the λ sweep (experiments/lambda_sweep): the measured
minimum angle, maximum radius-edge ratio and maximum roughness of every surface against the
theorem's bounds arcsin(1/(2+2λ)), 1+λ, 2β(λ); and the size |S| λ² / ∫ dA/lfs², which Theorem
6.1(iii) predicts to stay bounded (O(1/λ²) scaling).  Reads <out>/lambda_sweep.csv; writes
<out>/figures/lambda_bounds and <out>/figures/lambda_size (each figure as .pdf and .png).  Where
the sweep built ε-samples, also reads <out>/eps_sample.csv, eps_reference.csv and lfs_estimate.csv and writes
<out>/figures/size_ratio (size_ratio = |S| λ² / (|ε-sample| ε²) against λ for every surface and
ε: mean over the seeds, bars from the smallest to the largest) and <out>/figures/lfs_estimate
(the Voronoi-pole estimate of lfs against the exact lfs where one is known, and its relative
error per surface).  With several seeds per λ the lines of the first two figures join the means."""

import argparse
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from paper_common import loglog_slope, read_csv, readable_log_ticks, save_figure, surface_color  # noqa: E402


def completed(rows):
    return [r for r in rows if str(r["status"]) == "complete" and r["triangles"] > 0]


def by_lambda(rows, value, scale=1.0):
    """(λ, mean, min, max) of value over the rows (one per seed) at each λ, sorted by λ."""
    groups = {}
    for r in rows:
        groups.setdefault(float(r["lambda"]), []).append(value(r) * scale)
    return [(l, sum(v) / len(v), min(v), max(v)) for l, v in sorted(groups.items())]


def size_ratio_figure(out):
    """size_ratio against λ, one panel per ε (the default 0.1, 0.15, 0.19)."""
    meta, rows = read_csv(os.path.join(out, "eps_sample.csv"))
    rows = [r for r in rows if str(r["status"]) == "complete" and r["vertices"] > 0]
    if not rows:
        print("eps_sample.csv has no completed run: no size_ratio figure")
        return
    epsilons = sorted({float(r["epsilon"]) for r in rows})
    surfaces = sorted({r["surface"] for r in rows})
    fig, axes = plt.subplots(1, len(epsilons), figsize=(5 * len(epsilons), 4.2), squeeze=False)
    for ax, eps in zip(axes[0], epsilons):
        for name in surfaces:
            sel = [r for r in rows if r["surface"] == name and float(r["epsilon"]) == eps]
            if not sel:
                continue
            series = by_lambda(sel, lambda r: r["size_ratio"])
            analytic = sel[0]["lfs_source"] == "analytic"
            xs = [s[0] for s in series]
            ys = [s[1] for s in series]
            err = [[s[1] - s[2] for s in series], [s[3] - s[1] for s in series]]
            ax.errorbar(xs, ys, yerr=err, fmt="o-" if analytic else "s--", color=surface_color(name),
                        mfc=None if analytic else "white", capsize=3, ms=5,
                        label=f"{name} (|ε-sample| {sel[0]['eps_sample_vertices']})")
        ax.set_xlabel("λ")
        ax.set_ylabel("size_ratio = |S| λ² / (|ε-sample| ε²)")
        ax.set_title(f"ε = {eps:g}")
        ax.set_yscale("log")
        readable_log_ticks(ax.yaxis)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    seeds = sorted({int(r["seed"]) for r in rows})
    fig.suptitle("Theorem 6.1(iii) against real ε-samples: bounded as λ → 0 "
                 f"(filled: analytic lfs, open: Voronoi-pole estimate; {len(seeds)} seed(s), bars min–max; "
                 f"git {meta.get('git', '?')})", fontsize=10)
    fig.tight_layout()
    save_figure(fig, out, "size_ratio")


def lfs_estimate_figure(out):
    """The pole estimate against the exact lfs (left) and its relative error per surface (right)."""
    _, points = read_csv(os.path.join(out, "lfs_estimate.csv"))
    _, references = read_csv(os.path.join(out, "eps_reference.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    exact = [p for p in points if isinstance(p["lfs_analytic"], (int, float)) and not math.isnan(p["lfs_analytic"])]
    ax = axes[0]
    for name in sorted({p["surface"] for p in exact}):
        sel = [p for p in exact if p["surface"] == name]
        ax.loglog([p["lfs_analytic"] for p in sel], [p["lfs_estimate"] for p in sel], ".", ms=2,
                  color=surface_color(name), label=f"{name} ({len(sel)} points)")
    if exact:
        lo = min(min(p["lfs_analytic"], p["lfs_estimate"]) for p in exact)
        hi = max(max(p["lfs_analytic"], p["lfs_estimate"]) for p in exact)
        ax.loglog([lo, hi], [lo, hi], "k--", lw=1, label="estimate = lfs")
        ax.loglog([lo, hi], [1.1 * lo, 1.1 * hi], "k:", lw=0.8, label="±10 %")
        ax.loglog([lo, hi], [0.9 * lo, 0.9 * hi], "k:", lw=0.8)
    readable_log_ticks(ax.xaxis)
    readable_log_ticks(ax.yaxis)
    ax.set_xlabel("exact lfs (closed form)")
    ax.set_ylabel("Voronoi-pole estimate")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, markerscale=4)
    ax = axes[1]
    errors = {}
    for r in references:
        if isinstance(r["lfs_relative_error_max"], float) and not math.isnan(r["lfs_relative_error_max"]):
            errors[r["surface"]] = (r["lfs_relative_error_median"], r["lfs_relative_error_max"])
    names = sorted(errors)
    if names:
        xs = range(len(names))
        ax.bar([x - 0.2 for x in xs], [errors[n][0] for n in names], 0.4, label="median", color="tab:blue")
        ax.bar([x + 0.2 for x in xs], [errors[n][1] for n in names], 0.4, label="max", color="tab:orange")
        ax.set_xticks(list(xs))
        ax.set_xticklabels(names, rotation=20)
        ax.set_yscale("log")
        ax.legend(fontsize=8)
    ax.set_ylabel("relative error |estimate − lfs| / lfs over the sample")
    ax.grid(alpha=0.3, which="both", axis="y")
    fig.suptitle("lfs from the poles of the Voronoi diagram of a dense sample (Amenta–Bern)", fontsize=11)
    fig.tight_layout()
    save_figure(fig, out, "lfs_estimate")


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
            series = by_lambda([r for r in rows if r["surface"] == name], lambda r: r[measured], scale)
            ax.plot([s[0] for s in series], [s[1] for s in series], "o-", color=surface_color(name), label=name)
        ax.set_xlabel("λ")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    # Margins: measured / bound for the two upper bounds (≤ 1 means the bound holds); violations in red.
    ax = axes[3]
    for measured, bound, marker in (("max_radius_edge_ratio", "bound_max_radius_edge_ratio", "s"),
                                    ("max_roughness_rad", "bound_max_roughness_rad", "o")):
        for name in surfaces:
            series = by_lambda([r for r in rows if r["surface"] == name], lambda r: r[measured] / r[bound])
            ax.plot([s[0] for s in series], [s[1] for s in series], marker + "-", color=surface_color(name),
                    ms=4, lw=0.8)
            for x, y in ((r["lambda"], r[measured] / r[bound]) for r in rows if r["surface"] == name):
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
    save_figure(fig, args.out, "lambda_bounds")

    sized = [r for r in rows if isinstance(r["lfs_integral"], float) and not math.isnan(r["lfs_integral"])]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for name in surfaces:
        series = by_lambda([r for r in rows if r["surface"] == name], lambda r: r["vertices"])
        xs, ys = [1 / s[0] for s in series], [s[1] for s in series]
        label = name if len(xs) < 2 else f"{name} (slope {loglog_slope(xs, ys):.2f})"
        axes[0].loglog(xs, ys, "o-", color=surface_color(name), label=label)
    # Reference slope 2 through the coarsest run of the largest surface.
    biggest = max(surfaces, key=lambda n: max(r["vertices"] for r in rows if r["surface"] == n))
    anchor = min(((1 / float(r["lambda"]), r["vertices"]) for r in rows if r["surface"] == biggest))
    ref = sorted(1 / l for l in lambdas)
    axes[0].loglog(ref, [anchor[1] * (x / anchor[0]) ** 2 for x in ref], "k:", label="∝ 1/λ² (Theorem 6.1(iii))")
    readable_log_ticks(axes[0].xaxis, ref)  # the sweep's 1/λ, plainly
    readable_log_ticks(axes[0].yaxis)
    axes[0].set_xlabel("1/λ")
    axes[0].set_ylabel("vertices |S|")
    axes[0].grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=8)
    for name in sorted({r["surface"] for r in sized}):
        series = by_lambda([r for r in sized if r["surface"] == name],
                           lambda r: r["vertices_lambda2_over_lfs_integral"])
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
    save_figure(fig, args.out, "lambda_size")

    if os.path.exists(os.path.join(args.out, "eps_sample.csv")):
        size_ratio_figure(args.out)
    if os.path.exists(os.path.join(args.out, "lfs_estimate.csv")):
        lfs_estimate_figure(args.out)


if __name__ == "__main__":
    main()
