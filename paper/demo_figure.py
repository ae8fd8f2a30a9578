#!/usr/bin/env python3
"""The topology demo of experiments/compare_cgal: CGAL's Surface_mesher and Mesh_3 at coarse
settings against delmesh on thin_handle, two_blobs and near_sheets, each mesh captioned with the
components and genera the independent checker found.  Reads <out>/compare_cgal.csv and the OFF files
it names (<out>/meshes/compare_demo_*.off); writes <out>/figures/topology_demo.pdf and .png."""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from paper_common import read_csv, read_off, render_mesh, save_figure  # noqa: E402


def mesh_file(out, row):
    settings = str(row["parameters"]).replace(";", "_").replace("=", "_")
    return os.path.join(out, "meshes",
                        f"compare_{row['experiment']}_{row['surface']}_{row['method']}_{settings}.off")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="out", help="the experiments' output directory")
    args = parser.parse_args()
    _, rows = read_csv(os.path.join(args.out, "compare_cgal.csv"))
    demo = [r for r in rows if r["experiment"] == "demo"]
    if not demo:
        raise SystemExit("compare_cgal.csv has no demo rows")
    surfaces = list(dict.fromkeys(r["surface"] for r in demo))
    # Columns: every CGAL run of the demo (in CSV order: mesher × coarse radius), then delmesh.
    columns = list(dict.fromkeys((r["method"], r["parameters"]) for r in demo if r["method"] != "delmesh"))
    columns.append(("delmesh", None))
    fig = plt.figure(figsize=(3.6 * len(columns), 3.6 * len(surfaces)))
    for i, surface in enumerate(surfaces):
        for j, (method, parameters) in enumerate(columns):
            ax = fig.add_subplot(len(surfaces), len(columns), i * len(columns) + j + 1, projection="3d")
            match = [r for r in demo if r["surface"] == surface and r["method"] == method
                     and (parameters is None or r["parameters"] == parameters)]
            if not match or not os.path.exists(mesh_file(args.out, match[0])):
                ax.set_axis_off()
                ax.set_title(f"{surface} / {method}: no mesh", fontsize=8)
                continue
            row = match[0]
            points, triangles = read_off(mesh_file(args.out, row))
            verdict = "correct" if row["topology_correct"] == 1 else "WRONG"
            settings = " ".join(p for p in str(row["parameters"]).split(";") if p.split("=")[0] in
                                ("radius", "distance", "lambda"))
            title = (f"{surface} — {method} ({settings})\n{row['vertices']} vertices, {row['components']} comp., "
                     f"genus {row['genus_per_component']}: {verdict}")
            ax.view_init(elev=30, azim=-70)
            color = (0.62, 0.74, 0.86) if verdict == "correct" else (0.92, 0.62, 0.55)
            render_mesh(ax, points, triangles, title, color=color, edge_width=0.1)
            ax.title.set_fontsize(8)
    fig.suptitle("Coarse CGAL settings vs delmesh: topology found by the independent checker "
                 "(expected: thin_handle genus 1; two_blobs, near_sheets two spheres)", fontsize=11)
    fig.subplots_adjust(left=0, right=1, bottom=0, top=0.86, wspace=0, hspace=0.12)
    save_figure(fig, args.out, "topology_demo", dpi=130)


if __name__ == "__main__":
    main()
