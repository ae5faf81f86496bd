#!/usr/bin/python3
"""The threads scaling plot of docs/benchmarks.md ("Threads") from the table ThreadScaling prints.

    build/bin/ThreadScaling --threads 1,2 anymal_16 pyramid_20 box_pile_1000 > threads.txt
    scripts/plot_threads.py threads.txt [--out docs/img/threads_scaling.png]

Needs matplotlib (Debian: apt-get install python3-matplotlib). One line per scene: the measured
speed-up at each thread count (markers), Amdahl's estimate from the measured serial fraction
(dashed) and the bound of the islands, the largest spread over at most its sweep's parts
(solid), up to 64 threads.
"""
import argparse
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("plot_threads.py needs matplotlib: apt-get install python3-matplotlib")


def read(path):
    scenes = {}
    with open(path, encoding="utf-8") as f:
        header = None
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "scene":
                header = fields
                continue
            if header is None or len(fields) < len(header):
                continue
            row = dict(zip(header, fields))
            scene = scenes.setdefault(row["scene"],
                                      {"measured": [], "p": 0.0, "largest": 0.0, "parts": 1.0})
            scene["measured"].append((int(row["threads"]), float(row["speedup"])))
            scene["p"] = float(row["parallel"])
            scene["largest"] = float(row["largest"])
            scene["parts"] = float(row.get("parts", 1.0))
    return scenes


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("table")
    parser.add_argument("--out", default="docs/img/threads_scaling.png")
    args = parser.parse_args()
    scenes = read(args.table)
    if not scenes:
        sys.exit(f"{args.table}: no ThreadScaling rows")
    counts = [1, 2, 4, 8, 16, 32, 64]
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=80)
    for index, (name, s) in enumerate(sorted(scenes.items())):
        colour = f"C{index}"
        p, largest, parts = s["p"], s["largest"], s["parts"]
        ax.plot(counts, [1 / ((1 - p) + p / n) for n in counts], "--", color=colour, alpha=0.6)
        ax.plot(counts, [1 / ((1 - p) + p * max(largest / min(n, parts), 1 / n)) for n in counts],
                "-", color=colour,
                label=f"{name} (p = {p:.2f}, largest island {largest:.2f} in {parts:.0f} parts)")
        xs, ys = zip(*sorted(s["measured"]))
        ax.plot(xs, ys, "o", color=colour, markersize=7)
    ax.set_xscale("log", base=2)
    ax.set_xticks(counts)
    ax.set_xticklabels([str(n) for n in counts])
    ax.set_xlabel("threads")
    ax.set_ylabel("speed-up of a step")
    ax.set_title("measured (dots), islands, the largest over its parts (solid), Amdahl (dashed)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
