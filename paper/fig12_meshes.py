#!/usr/bin/env python3
"""Fig. 12 of the paper: DelMesh meshes of a smooth sphere, torus and metaball given by implicit
equations.  Reads the OFF files written by experiments/lambda_sweep (out/meshes/sweep_<name>_l<λ>.off)
and the sweep CSV (for the vertex counts and checker results in the captions); writes
<out>/figures/fig12.pdf and .png."""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from paper_common import read_csv, read_off, render_mesh, save_figure  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="out", help="the experiments' output directory")
    parser.add_argument("--lambda", dest="lam", default="0.06", help="which sweep meshes to show")
    parser.add_argument("--surfaces", default="sphere,torus,metaball")
    args = parser.parse_args()

    _, rows = read_csv(os.path.join(args.out, "lambda_sweep.csv"))
    by_key = {(r["surface"], float(r["lambda"])): r for r in rows}
    names = args.surfaces.split(",")
    fig = plt.figure(figsize=(4 * len(names), 4.4))
    for index, name in enumerate(names):
        path = os.path.join(args.out, "meshes", f"sweep_{name}_l{args.lam}.off")
        ax = fig.add_subplot(1, len(names), index + 1, projection="3d")
        if not os.path.exists(path):
            ax.set_axis_off()
            ax.set_title(f"{name}: no mesh\n({os.path.basename(path)} missing)", fontsize=9)
            continue
        points, triangles = read_off(path)
        row = by_key.get((name, float(args.lam)), {})
        caption = f"{name}, λ = {args.lam}: {len(points)} vertices"
        if row:
            caption += (f"\nmin angle {row['min_angle_deg']:.1f}°, genus {row['genus_per_component']}"
                        f" ({'correct' if row['topology_correct'] == 1 else 'WRONG'})")
        ax.view_init(elev=25, azim=-60)
        render_mesh(ax, points, triangles, caption)
    fig.suptitle("DelMesh on implicit surfaces (cf. Fig. 12)", fontsize=11)
    fig.subplots_adjust(left=0, right=1, bottom=0, top=0.86, wspace=0, hspace=0.12)
    save_figure(fig, args.out, "fig12")


if __name__ == "__main__":
    main()
