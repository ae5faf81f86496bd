#!/usr/bin/python3
"""Work-precision plots from the CSV of `coulomb bench --out FILE` (docs/benchmarks.md).

    scripts/plot_bench.py results.csv [--out-dir docs/img]

Needs matplotlib (Debian: apt-get install python3-matplotlib). Writes, for the parts present:
  bench_corpus_work_precision.png  common residual against ms per solve, one panel per fc3d problem,
                                   one line per solver over the tolerance ladder (part corpus)
  bench_scenes_work_precision.png  mean common residual against ms/step, one panel per scene: the
                                   iteration-cap sweep of each solver alone (lines) and each solver
                                   at the world's defaults (large markers) (parts sweep, scenes)
  bench_nu_iterations.png          ac_newton iterations against nu on our scenes (island solves)
                                   and nu-hat on the corpus (AC11 figure 10) (parts nu, corpus)
  bench_scaling.png                ms/step against bodies for stacks, pyramids and piles, and
                                   against links for the ball chains (parts scenes, joints)
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter
except ImportError:
    sys.exit("plot_bench.py needs matplotlib: apt-get install python3-matplotlib")

SOLVER_COLOURS = {"pgs": "tab:blue", "bgs": "tab:orange", "ac_newton": "tab:green",
                  "auto": "tab:red", "prox": "tab:purple", "lemke": "tab:brown"}
DPI = 80


def number(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return math.nan
    return value


def colour(solver):
    return SOLVER_COLOURS.get(solver.rstrip("!"), "tab:gray")


def positive(value, floor=1e-17):
    """Log axes: a residual of exactly 0 is drawn at the floor."""
    return value if value > floor else floor


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("ms", "iterations_mean", "iterations_max", "residual_mean", "residual_max",
                    "max_drift", "energy_change", "joint_gap", "nu"):
            r[key] = number(r.get(key))
        r["size"] = int(r.get("size") or 0)
    return rows


def grid(count, width=3.0, height=2.4, columns=None):
    columns = columns or min(count, max(1, math.ceil(math.sqrt(count * 1.3))))
    lines = math.ceil(count / columns)
    fig, axes = plt.subplots(lines, columns, figsize=(width * columns, height * lines),
                             squeeze=False)
    for ax in axes.flat[count:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:count])


def legend_of_solvers(fig, solvers, extra=()):
    handles = [plt.Line2D([], [], color=colour(s), marker="o", label=s) for s in solvers]
    fig.legend(handles=handles + list(extra), loc="upper center", ncol=len(handles) + len(extra),
               frameon=False)


def plot_corpus(rows, out):
    corpus = [r for r in rows if r["part"] == "corpus"]
    if not corpus:
        return None
    problems = []
    for r in corpus:
        if r["item"] not in problems:
            problems.append(r["item"])
    solvers = sorted({r["solver"] for r in corpus}, key=list(SOLVER_COLOURS).index)
    fig, axes = grid(len(problems), width=2.6, height=2.1)
    for ax, problem in zip(axes, problems):
        mine = [r for r in corpus if r["item"] == problem]
        for solver in solvers:
            pts = sorted((r["ms"], positive(r["residual_max"]), r["status"]) for r in mine
                         if r["solver"] == solver)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=colour(solver), lw=1)
            for x, y, status in pts:  # hollow marker: the tolerance was not reached
                ax.plot(x, y, "o", ms=3.5, color=colour(solver),
                        mfc=colour(solver) if status == "converged" else "none")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{problem[:26]} ({mine[0]['size']} c)", fontsize=7)
        ax.tick_params(labelsize=6)
    fig.supxlabel("ms per solve (median)")
    fig.supylabel("common residual e_rel")
    legend_of_solvers(fig, solvers)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    return save(fig, out, "bench_corpus_work_precision.png")


def plot_scenes(rows, out):
    sweep = [r for r in rows if r["part"] == "sweep"]
    scenes = [r for r in rows if r["part"] == "scenes"]
    names = []
    for r in sweep + scenes:
        if r["item"] not in names:
            names.append(r["item"])
    if not names:
        return None
    fig, axes = grid(len(names), width=3.4, height=2.8)
    solvers = []
    for ax, name in zip(axes, names):
        for solver in sorted({r["solver"] for r in sweep if r["item"] == name}):
            pts = sorted((r["ms"], positive(r["residual_mean"]))
                         for r in sweep if r["item"] == name and r["solver"] == solver)
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", ms=3, lw=1,
                    color=colour(solver))
            solvers.append(solver.rstrip("!"))
        for r in scenes:
            if r["item"] == name:
                ax.plot(r["ms"], positive(r["residual_mean"]), marker="*", ms=11,
                        color=colour(r["solver"]), mec="black", mew=0.5, ls="none")
                solvers.append(r["solver"].rstrip("!"))
                if r["note"].startswith("capped"):
                    ax.annotate("capped", (r["ms"], positive(r["residual_mean"])), fontsize=5)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(name, fontsize=8)
        ax.tick_params(labelsize=6)
    fig.supxlabel("ms per step (median)")
    fig.supylabel("mean common residual per island solve")
    order = list(SOLVER_COLOURS)
    unique = sorted(set(solvers), key=lambda s: order.index(s) if s in order else 99)
    star = plt.Line2D([], [], color="gray", marker="*", ms=9, ls="none",
                      label="world defaults (tol 1e-6, fallbacks)")
    line = plt.Line2D([], [], color="gray", marker="o", ms=3, label="alone, iteration cap swept")
    legend_of_solvers(fig, unique, extra=(star, line))
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    return save(fig, out, "bench_scenes_work_precision.png")


def plot_nu(rows, out):
    nu_rows = [r for r in rows if r["part"] == "nu"]
    corpus = [r for r in rows if r["part"] == "corpus" and r["solver"] == "ac_newton"
              and r["variant"] == "tol=1e-08" and not math.isnan(r["nu"])]
    if not nu_rows and not corpus:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharey=True)
    ax = axes[0]
    scenes = []
    for r in nu_rows:
        if r["item"] not in scenes:
            scenes.append(r["item"])
    cmap = plt.get_cmap("tab10")
    for k, scene in enumerate(scenes):
        mine = [r for r in nu_rows if r["item"] == scene]
        size = [8 + 4 * math.sqrt(int(r["repeats"])) for r in mine]
        ax.scatter([r["nu"] for r in mine], [r["iterations_mean"] for r in mine], s=size,
                   color=cmap(k % 10), alpha=0.7, label=scene)
        ax.scatter([r["nu"] for r in mine], [r["iterations_max"] for r in mine], s=12,
                   marker="x", color=cmap(k % 10), alpha=0.7)
    ax.set_title("scenes: island solves (dot mean, x max; area ~ count)", fontsize=8)
    ax.set_xlabel("nu = 3 n / m")
    ax.set_ylabel("ac_newton iterations (cap 200)")
    ax.legend(fontsize=6, frameon=False)
    ax = axes[1]
    for r in corpus:
        ok = r["status"] == "converged"
        ax.plot(r["nu"], max(r["iterations_max"], 0.8), "o", ms=5, color="tab:green",
                mfc="tab:green" if ok else "none")
    ax.set_title("fc3d corpus, tol 1e-8 (hollow: not reached)", fontsize=8)
    ax.set_xlabel("nu-hat = 3 n / rank W")
    for a in axes:
        a.set_yscale("log")
        for x in (1.0, 1.5):
            a.axvline(x, color="gray", lw=0.6, ls=":")
        a.tick_params(labelsize=7)
    fig.tight_layout()
    return save(fig, out, "bench_nu_iterations.png")


def plot_scaling(rows, out):
    scenes = [r for r in rows if r["part"] == "scenes"]
    joints = [r for r in rows if r["part"] == "joints"]
    if not scenes and not joints:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    ax = axes[0]
    families = defaultdict(lambda: defaultdict(list))  # family -> solver -> (bodies, ms, capped)
    for r in scenes:
        family = r["item"].rsplit("_", 1)[0] if r["item"][-1].isdigit() else r["item"]
        families[family][r["solver"]].append((r["size"], r["ms"], r["note"].startswith("capped")))
    markers = ["o", "s", "^", "D", "v"]
    for f, (family, by_solver) in enumerate(sorted(families.items())):
        for solver, pts in sorted(by_solver.items()):
            pts.sort()
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", marker=markers[f % 5], ms=4,
                    lw=1, color=colour(solver), label=f"{family} {solver}")
            for x, y, capped in pts:
                if capped:
                    ax.plot(x, y, "o", ms=9, mfc="none", color="black", mew=0.6)
    ax.set_title("stacks, pyramids, piles (black ring: run capped)", fontsize=8)
    ax.set_xlabel("dynamic bodies")
    ax.set_ylabel("ms per step (median)")
    ax.legend(fontsize=5, frameon=False, ncol=2)
    ax = axes[1]
    series = defaultdict(list)
    for r in joints:
        series[(r["solver"], r["variant"])].append((r["size"], r["ms"]))
    for (solver, policy), pts in sorted(series.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-" if policy != "baumgarte" else "--",
                marker="o", ms=4, lw=1, color=colour(solver), label=f"{solver} {policy}")
    ax.set_title("ball chains, dt 0.01 (docs/scene-specifications.md A6)", fontsize=8)
    ax.set_xlabel("links")
    ax.legend(fontsize=6, frameon=False)
    for a in axes:
        a.set_xscale("log")
        a.set_yscale("log")
        a.tick_params(labelsize=7)
    fig.tight_layout()
    return save(fig, out, "bench_scaling.png")


def save(fig, out, name):
    for ax in fig.axes:  # log axes: labels at the decades only
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.yaxis.set_minor_formatter(NullFormatter())
    path = os.path.join(out, name)
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", help="CSV written by coulomb bench --out")
    parser.add_argument("--out-dir", default="docs/img", help="folder of the PNGs")
    args = parser.parse_args()
    if not os.path.isfile(args.csv):
        sys.exit(f"plot_bench.py: no file '{args.csv}'")
    rows = read_rows(args.csv)
    if not rows or "part" not in rows[0]:
        sys.exit(f"plot_bench.py: '{args.csv}' is not a `coulomb bench --out` CSV")
    os.makedirs(args.out_dir, exist_ok=True)
    for plot in (plot_corpus, plot_scenes, plot_nu, plot_scaling):
        path = plot(rows, args.out_dir)
        if path:
            print(f"{path}: {os.path.getsize(path) // 1024} kB")


if __name__ == "__main__":
    main()
