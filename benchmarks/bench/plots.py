"""The suite's charts (PNG, matplotlib's Agg backend: no display needed)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .pfm import read_pfm  # noqa: E402

# One colour and marker per method, the same in every chart.
STYLE = {
    "pt-uniform": ("#7f7f7f", "o"),
    "pt-power": ("#1f77b4", "s"),
    "learned": ("#2ca02c", "^"),
    "cv": ("#ff7f0e", "v"),
    "cms": ("#d62728", "D"),
}


def convergence(title, series, out):
    """relMSE against render time, log-log, one line per method. series: {method: [(seconds, relmse)]}."""
    fig, ax = plt.subplots(figsize=(5.2, 4.0), dpi=110)
    for method, points in series.items():
        points = sorted(p for p in points if p[0] > 0 and p[1] > 0)
        if not points:
            continue
        colour, marker = STYLE.get(method, (None, "o"))
        ax.plot([p[0] for p in points], [p[1] for p in points], marker=marker, color=colour, label=method, lw=1.5, ms=4)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relMSE")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


# Pass groups of the time breakdown, in stacking order: the statistics are the extra time of the
# sample passes that gathered them over those that did not (suite.py computes it).
GROUPS = ["trace", "shade", "statistics", "solve", "other"]
GROUP_COLOURS = {"trace": "#4c72b0", "shade": "#55a868", "statistics": "#c44e52", "solve": "#8172b2",
                 "other": "#ccb974"}


def pass_breakdown(title, breakdown, out):
    """Stacked bars of GPU milliseconds per sample per pass group. breakdown: {method: {group: ms}}."""
    methods = list(breakdown)
    fig, ax = plt.subplots(figsize=(5.2, 3.6), dpi=110)
    bottom = np.zeros(len(methods))
    for group in GROUPS:
        values = np.array([breakdown[m].get(group, 0.0) for m in methods])
        ax.bar(methods, values, bottom=bottom, label=group, color=GROUP_COLOURS[group])
        bottom += values
    ax.set_ylabel("GPU ms per sample")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def error_images(title, reference_png, panels, out):
    """The reference beside one false-colour relative-error map per method (the per-pixel terms of
    relMSE, log scale). panels: [(label, pfm path)]."""
    n = len(panels) + 1
    fig, axes = plt.subplots(1, n, figsize=(2.3 * n + 0.6, 2.4), dpi=110)
    axes[0].imshow(plt.imread(reference_png))
    axes[0].set_title("reference", fontsize=8)
    image = None
    for ax, (label, pfm) in zip(axes[1:], panels):
        error = np.clip(read_pfm(pfm), 1e-5, 1e2)
        image = ax.imshow(np.log10(error), cmap="inferno", vmin=-4, vmax=1)
        ax.set_title(label, fontsize=8)
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    if image is not None:
        bar = fig.colorbar(image, ax=list(axes[1:]), fraction=0.025, pad=0.02)
        bar.set_label("log10 relative squared error", fontsize=7)
        bar.ax.tick_params(labelsize=7)
    fig.suptitle(title, fontsize=9)
    fig.savefig(out, bbox_inches="tight")
    plt.close(fig)


def knob(title, xlabels, relmse, ms_per_sample, out):
    """One accuracy knob: relMSE (bars) and time per sample (line) for each setting."""
    fig, ax = plt.subplots(figsize=(4.6, 3.2), dpi=110)
    x = np.arange(len(xlabels))
    ax.bar(x, relmse, color="#4c72b0", alpha=0.8)
    ax.set_xticks(x, xlabels)
    ax.set_ylabel("relMSE (equal spp)", color="#4c72b0")
    twin = ax.twinx()
    twin.plot(x, ms_per_sample, color="#c44e52", marker="o")
    twin.set_ylabel("ms per sample", color="#c44e52")
    twin.set_ylim(bottom=0)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
