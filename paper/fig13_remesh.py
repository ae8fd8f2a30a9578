#!/usr/bin/env python3
"""Fig. 13 of the paper: DelMesh remeshing triangulated surfaces.  One row per input mesh, three
columns: the input; the mesh after SampleTopology (topology phase); the mesh after Quality and
Smooth (final).  Reads what experiments/remesh writes: <out>/remesh/<name>_{input,topology,final}.off
and <out>/remesh.csv (vertex counts, status, genus and quality for the captions); writes
<out>/figures/fig13.pdf and .png."""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from paper_common import read_csv, read_off, render_mesh, save_figure  # noqa: E402

COLUMNS = [("input", "input"), ("topology", "after SampleTopology"), ("final", "after Quality and Smooth")]


def genus_text(genus):
    """The checker's genus list ("1;1"), with -1 (undefined) spelled out."""
    genera = str(genus).split(";")
    if "-1" in genera:
        return "not a closed orientable manifold"
    return "genus " + ", ".join(genera)


def caption(name, column, points, row):
    """The panel's title: what it shows, its size and, for the outputs, the run's figures."""
    text = f"{name}, {dict(COLUMNS)[column]}: {len(points)} vertices"
    if column == "input" and row:
        text += f"\n{genus_text(row['input_genus'])}"
    elif row:
        same = "as the input" if row["topology_matches"] == 1 else "DIFFERS from the input"
        genus = genus_text(row["output_genus"])
        # A long genus text (a defect) gets a line of its own, so that the caption fits the panel.
        text += f"\n{row['status']}, {genus} ({same})" if len(genus) < 20 else f"\n{row['status']}: {genus}\n({same})"
        details = []
        if column == "final":
            details.append(f"min angle {row['min_angle_deg']:.1f}°")
        if row["floor_reached"] == 1:
            details.append("floor reached")
        if details:
            text += "\n" + ", ".join(details)
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="out", help="the experiments' output directory")
    parser.add_argument("--meshes", default="elephant,eight,knot1", help="input names (file stems)")
    args = parser.parse_args()

    csv_path = os.path.join(args.out, "remesh.csv")
    rows = read_csv(csv_path)[1] if os.path.exists(csv_path) else []
    by_key = {(r["mesh"], r["phase"]): r for r in rows}
    names = args.meshes.split(",")
    fig = plt.figure(figsize=(12, 4 * len(names)))
    for r, name in enumerate(names):
        for c, (column, _) in enumerate(COLUMNS):
            ax = fig.add_subplot(len(names), len(COLUMNS), r * len(COLUMNS) + c + 1, projection="3d")
            path = os.path.join(args.out, "remesh", f"{name}_{column}.off")
            if not os.path.exists(path):
                ax.set_axis_off()
                ax.set_title(f"{name}: no mesh\n({os.path.basename(path)} missing)", fontsize=9)
                continue
            points, triangles = read_off(path)
            row = by_key.get((name, "topology" if column == "input" else column))
            ax.view_init(elev=20, azim=-60)
            render_mesh(ax, points, triangles, caption(name, column, points, row), edge_width=0.1)
    fig.suptitle("DelMesh remeshing triangulated surfaces (cf. Fig. 13)", fontsize=11, y=0.995)
    fig.subplots_adjust(left=0, right=1, bottom=0, top=1 - 1.2 / fig.get_figheight(), wspace=0, hspace=0.3)
    save_figure(fig, args.out, "fig13")


if __name__ == "__main__":
    main()
