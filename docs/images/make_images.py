"""Regenerates the pictures of the README: docs/images/surfaces.png, the meshes delmesh makes of
three catalog surfaces at the default lambda 0.06 (genus2, tanglecube, thin_handle).

    /usr/bin/python3 docs/images/make_images.py [--delmesh build/delmesh] [--out docs/images]

Needs the program (a normal build) and python3-matplotlib; runs in a few seconds.
"""
import argparse
import os
import subprocess
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LightSource

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SURFACES = ("genus2", "tanglecube", "thin_handle")


def read_off(path):
    """Vertices and triangles of an ASCII OFF file as `delmesh mesh` writes it."""
    with open(path) as f:
        words = f.read().split()
    nv, nf = int(words[1]), int(words[2])
    vertices = np.array(words[4:4 + 3 * nv], dtype=float).reshape(nv, 3)
    faces = np.array(words[4 + 3 * nv:4 + 3 * nv + 4 * nf], dtype=int).reshape(nf, 4)
    return vertices, faces[:, 1:]


def mesh(delmesh, surface, directory):
    off = os.path.join(directory, surface + ".off")
    subprocess.run([delmesh, "mesh", "--surface", surface, "--out", off,
                    "--stats", os.path.join(directory, surface + ".json"), "--quiet"], check=True)
    return read_off(off)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--delmesh", default=os.path.join(ROOT, "build", "delmesh"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "images"))
    args = parser.parse_args()
    figure = plt.figure(figsize=(9, 3))
    light = LightSource(azdeg=315, altdeg=45)
    with tempfile.TemporaryDirectory() as directory:
        for i, surface in enumerate(SURFACES):
            vertices, triangles = mesh(args.delmesh, surface, directory)
            axes = figure.add_subplot(1, len(SURFACES), i + 1, projection="3d")
            x, y, z = vertices.T
            axes.plot_trisurf(x, y, z, triangles=triangles, color="lightsteelblue", edgecolor="#202830",
                              linewidth=0.15, shade=True, lightsource=light)
            axes.set_box_aspect(vertices.max(axis=0) - vertices.min(axis=0))
            axes.view_init(elev=35, azim=-60)
            axes.set_axis_off()
            axes.set_title(f"{surface}: {len(vertices)} vertices", fontsize=9, y=0.92)
    figure.subplots_adjust(left=0, right=1, bottom=0, top=1, wspace=0)
    png = os.path.join(args.out, "surfaces.png")
    figure.savefig(png, dpi=110, bbox_inches="tight", pad_inches=0.02)
    print("wrote", png, os.path.getsize(png), "bytes")


if __name__ == "__main__":
    main()
