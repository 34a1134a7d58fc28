"""The cost of a body resting on a triangle mesh against the mesh's triangle count (issue 34), from
`bench_mesh_cost --csv FILE`: a plot (ns per call of ODE's own collider, gdcontact through the ODE
adapter and gdcontact's core query, one panel per body, the triangle count on a log axis) and the
table of docs/meshes.md on stdout."""
import argparse
import csv

from gdcreport import plots

CONTENDERS = [("ode_ns", "ODE's own collider", "tab:red", "s"),
              ("adapter_ns", "gdcontact through the adapter", "tab:blue", "o"),
              ("core_ns", "gdcontact's core query", "tab:green", "^")]
BODIES = [("box", "unit box (ODE: box–trimesh)"), ("hull8", "8-vertex hull (ODE: convex–trimesh, libccd)")]


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        row["triangles"] = int(row["triangles"])
        for key, *_ in CONTENDERS:
            row[key] = float(row[key])
    return rows


def plot(rows, out):
    figure, axes = plots.plt.subplots(1, len(BODIES), figsize=(10, 3.8), sharey=True)
    for ax, (body, title) in zip(axes, BODIES):
        mine = sorted((r for r in rows if r["body"] == body), key=lambda r: r["triangles"])
        xs = [r["triangles"] for r in mine]
        for key, label, colour, marker in CONTENDERS:
            ax.plot(xs, [r[key] for r in mine], marker=marker, color=colour, label=label)
        ax.set_xscale("log")
        plots.plain_log_ticks(ax.xaxis, subs=(1.0,))
        ax.set_xlabel("triangles in the mesh")
        ax.set_title(title, fontsize=9)
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("ns per call (median over rounds)")
    axes[0].legend(fontsize=8, loc="lower left")
    plots.save_figure(figure, out)


def table(rows):
    lines = ["| triangles | body | ODE (ns/call) | gdcontact adapter (ns/call) | core (ns/call) | "
             "ratio to ODE: adapter / core | contacts ODE / adapter (core) |",
             "|---:|---|---:|---:|---:|---|---|"]
    for r in sorted(rows, key=lambda r: (r["triangles"], r["body"])):
        body = "box" if r["body"] == "box" else "8-vertex hull"
        lines.append(f"| {r['triangles']} | {body} | {r['ode_ns']:.0f} | {r['adapter_ns']:.0f} | {r['core_ns']:.0f} | "
                     f"{r['adapter_ns'] / r['ode_ns']:.2f} / {r['core_ns'] / r['ode_ns']:.2f} | "
                     f"{r['ode_contacts']} / {r['adapter_contacts']} (core {r['core_contacts']}) |")
    return "\n".join(lines)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("csv", help="the file bench_mesh_cost --csv wrote")
    parser.add_argument("--plot", default="docs/images/mesh_cost.png", help="where the plot goes")
    args = parser.parse_args(argv)
    rows = read(args.csv)
    if not rows:
        raise SystemExit(f"{args.csv}: no rows")
    plot(rows, args.plot)
    print(table(rows))
    return 0
