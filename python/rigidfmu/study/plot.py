"""The plot of a study: per metric, the distribution over the runs that finished (a
histogram) and the metric against each varied value (one point per run)."""
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from rigidfmu.errors import StudyError  # noqa: E402


def varied_columns(frame):
    """The design's numeric columns that take more than one value."""
    return [c for c in frame.columns
            if c.split(":")[0] in ("parameter", "scene", "input") and frame[c].dtype.kind in "if"
            and frame[c].nunique() > 1]


def plot(frame, study, png):
    ok = frame[frame["status"] == "ok"]
    metrics = [f"metric:{m}" for m in study.metrics]
    factors = varied_columns(frame)
    if not metrics:
        raise StudyError("study: --plot needs metrics in the study file")
    cols = 1 + len(factors)
    fig, axes = plt.subplots(len(metrics), cols, figsize=(4.2 * cols, 3.4 * len(metrics)),
                             squeeze=False)
    for row, metric in zip(axes, metrics):
        values = ok[metric].to_numpy(dtype=float)
        finite = values[np.isfinite(values)]
        name = metric.split(":", 1)[1]
        row[0].hist(finite, bins=30, color="tab:blue", edgecolor="white")
        row[0].set_xlabel(name)
        row[0].set_ylabel("runs")
        row[0].set_title(f"{name}: mean {np.mean(finite):.3g}, sd {np.std(finite):.3g}"
                         if len(finite) else f"{name}: no finite values", fontsize=9)
        for ax, factor in zip(row[1:], factors):
            ax.scatter(ok[factor], values, s=8, alpha=0.6)
            ax.set_xlabel(factor.split(":", 1)[1])
            ax.set_ylabel(name)
    failed = len(frame) - len(ok)
    fig.suptitle(f"{study.name}: {len(frame)} runs ({failed} failed)")
    fig.tight_layout()
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png, dpi=110)
    plt.close(fig)
