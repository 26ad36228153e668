"""Plot the CSV of mesh-projection-bench: time per target cell against the
number of cells (log-log), per stage and for the comparisons.

    /usr/bin/python3 Benchmarks/plot_benchmark.py bench.csv bench.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    dims = sorted({r["dim"] for r in rows})
    fig, axes = plt.subplots(1, len(dims), figsize=(6.5 * len(dims), 4.8), squeeze=False)
    series = [("total", "projection, all stages (kernel)", "-o"),
              ("search", "search + intersections + integrals", "-s"),
              ("filter_1_thread", "VTK filter, 1 thread", "--o"),
              ("filter_2_threads", "VTK filter, 2 threads", "--^"),
              ("locator", "locator search (vtkStaticCellLocator)", ":d"),
              ("brute", "brute force", ":x"),
              ("resample", "Resample With Dataset (probing)", "-.v")]
    for ax, dim in zip(axes[0], dims):
        sub = [r for r in rows if r["dim"] == dim]
        n = [float(r["target_cells"]) for r in sub]
        for key, label, style in series:
            points = [(x, float(r[key]) / x * 1e6) for x, r in zip(n, sub) if float(r[key]) > 0]
            if points:
                ax.loglog(*zip(*points), style, label=label)
        ax.set_title("%sD: %s" % (dim, "triangles" if dim == "2" else "tetrahedra"))
        ax.set_xlabel("target cells (source: about as many)")
        ax.set_ylabel("microseconds per target cell")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
