#!/usr/bin/env python3
"""The CGAL comparison table (experiments/compare_cgal): per experiment, surface and mesher the
vertices, minimum angle, topology found by the independent checker, seconds and seconds per vertex,
plus the ratio of delmesh's seconds per vertex to Mesh_3's (for a benchmark case run in several
rounds, `compare_cgal --repeat K`: the median ratio of the rounds and its range; each round's rows
carry their round number).  Reads <out>/compare_cgal.csv only;
writes <out>/tables/compare_cgal.md and <out>/tables/compare_cgal.tex and prints the Markdown."""

import argparse
import math
import os

from paper_common import output_path, read_csv


def fmt(value, digits=3):
    if isinstance(value, float):
        if math.isnan(value):
            return "–"
        return f"{value:.{digits}g}"
    return str(value)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="out", help="the experiments' output directory")
    args = parser.parse_args()
    meta, rows = read_csv(os.path.join(args.out, "compare_cgal.csv"))

    header = ["experiment", "surface", "mesher", "parameters", "vertices", "min angle (°)", "genus found",
              "expected", "topology", "seconds", "µs/vertex"]
    lines = []
    for r in rows:
        per_vertex = r["seconds_per_vertex"]
        parameters = str(r["parameters"]).replace(";", " ")
        if int(r.get("round", 1)) > 1:
            parameters += f" (round {r['round']})"
        lines.append([r["experiment"], r["surface"], r["method"], parameters,
                      fmt(r["vertices"]), fmt(float(r["min_angle_deg"]), 3), str(r["genus_per_component"]),
                      str(r["expected_genus"]), "ok" if r["topology_correct"] == 1 else "**wrong**",
                      fmt(float(r["seconds"]), 3), fmt(float(per_vertex) * 1e6, 3)])
    ratios = []
    # benchmark: each case is a Surface_mesher row, then per round a Mesh_3 row and one delmesh row
    # per thread count (compare_cgal --threads-compare adds a second); the rounds of a case follow
    # one another (round 1 starts a case).  Ratios are kept per thread count.
    last_m3 = None
    rounds = {}  # the current case's ratios, by delmesh's thread count
    for r in rows + [None]:
        if r is None or (r["experiment"] == "benchmark" and r["method"] == "mesh_3" and int(r.get("round", 1)) == 1):
            for threads, values in rounds.items():
                values = sorted(values)
                n = len(values)
                middle = values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])
                spread = f" (median of {n} rounds, {values[0]:.2f}–{values[-1]:.2f})" if n > 1 else ""
                label = case[1] + (f"; delmesh threads={threads}" if threads is not None else "")
                ratios.append(("benchmark", case[0], label, middle, spread))
            rounds = {}
        if r is None or r["experiment"] != "benchmark":
            continue
        if r["method"] == "mesh_3":
            last_m3 = r
            case = (r["surface"], r["parameters"])
        elif r["method"] == "delmesh" and r["vertices"] and last_m3 and last_m3["vertices"]:
            threads = next((p.split("=", 1)[1] for p in str(r["parameters"]).split(";")
                            if p.startswith("threads=")), None)
            rounds.setdefault(threads, []).append(float(r["seconds_per_vertex"]) / float(last_m3["seconds_per_vertex"]))
    for experiment in ("coarsest",):
        for surface in sorted({r["surface"] for r in rows if r["experiment"] == experiment}):
            sel = [r for r in rows if r["experiment"] == experiment and r["surface"] == surface]
            dm = [r for r in sel if r["method"] == "delmesh" and r["vertices"]]
            m3 = [r for r in sel if r["method"] == "mesh_3" and r["topology_correct"] == 1 and r["vertices"]]
            if experiment == "coarsest":
                m3 = m3[:1]  # the ladder runs coarse first: the first correct one is the coarsest
            if dm and m3:
                ratio = float(dm[0]["seconds_per_vertex"]) / float(m3[-1]["seconds_per_vertex"])
                ratios.append((experiment, surface, m3[-1]["parameters"], ratio, ""))

    md = [f"CGAL comparison (git {meta.get('git', '?')}, CGAL {meta.get('cgal', '?')}, {meta.get('date', '')})", ""]
    md.append("| " + " | ".join(header) + " |")
    md.append("|" + "---|" * len(header))
    md.extend("| " + " | ".join(line) + " |" for line in lines)
    md.append("")
    for experiment, surface, params, ratio, spread in ratios:
        md.append(f"- {experiment} {surface}: delmesh seconds per vertex / Mesh_3's ({params}) = {ratio:.2f}"
                  + spread + (" (target ≤ 3)" if experiment == "benchmark" else ""))
    text = "\n".join(md) + "\n"
    with open(output_path(args.out, "tables", "compare_cgal.md"), "w") as f:
        f.write(text)

    def tex_escape(s):
        return str(s).replace("_", r"\_").replace("%", r"\%").replace("**", "")
    tex = [r"\begin{tabular}{lllrrlllrr}", r"\hline",
           " & ".join(["exp.", "surface", "mesher", "vertices", "min angle", "genus", "expected", "topology",
                       "s", r"$\mu$s/vertex"]) + r" \\", r"\hline"]
    for line in lines:
        cells = [line[0], line[1], line[2], line[4], line[5], line[6], line[7], line[8], line[9], line[10]]
        tex.append(" & ".join(tex_escape(c) for c in cells) + r" \\")
    tex += [r"\hline", r"\end{tabular}"]
    with open(output_path(args.out, "tables", "compare_cgal.tex"), "w") as f:
        f.write("\n".join(tex) + "\n")
    print(text)


if __name__ == "__main__":
    main()
