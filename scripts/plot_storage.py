#!/usr/bin/python3
"""Plots the columns of OpenSim storage (.sto) files against time, one panel per file, into a PNG.

usage: scripts/plot_storage.py OUT.png FILE.sto [FILE.sto ...]
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_storage(path):
    with open(path) as f:
        lines = f.read().splitlines()
    title = lines[0]
    start = lines.index("endheader") + 1
    columns = lines[start].split("\t")
    rows = [[float(x) for x in line.split()] for line in lines[start + 1:] if line.strip()]
    return title, columns, rows


def main(out, paths):
    fig, axes = plt.subplots(len(paths), 1, figsize=(9, 3.2 * len(paths)), sharex=True, squeeze=False)
    for ax, path in zip(axes[:, 0], paths):
        title, columns, rows = read_storage(path)
        times = [r[0] for r in rows]
        for c, name in enumerate(columns[1:], start=1):
            ax.plot(times, [r[c] for r in rows], label=name, linewidth=1.2)
        ax.set_title(title)
        ax.grid(alpha=0.3)
        if len(columns) <= 13:
            ax.legend(fontsize=7, ncol=3, loc="upper right")
    axes[-1, 0].set_xlabel("time (s)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"plot: {out}")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2:])
