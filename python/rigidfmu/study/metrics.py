"""The metrics mini-language of a study: a metric is {"of": SIGNAL, "reduce": R}, with
SIGNAL one output name, or a list of names whose Euclidean norm is taken at each
communication point, and R one of the reductions below. Nothing is evaluated as code.
"""
import numpy as np

from rigidfmu.errors import StudyError

REDUCTIONS = {
    "initial": "the value at t = 0",
    "final": "the value at stopTime",
    "max": "the largest value",
    "min": "the smallest value",
    "mean": "the mean over the communication points",
    "time_of_max": "the first time the largest value is reached",
    "time_of_min": "the first time the smallest value is reached",
    "settling_time": "the first time from which |value| <= threshold until the end (NaN: never)",
}


class MetricError(StudyError):
    """A metric of a study file that breaks a rule."""


def check_metric(name, spec):
    where = f"metrics.{name}"
    if not isinstance(spec, dict) or not set(spec) <= {"of", "reduce", "threshold"}:
        raise MetricError(f"{where}: must be {{\"of\": NAME or [NAMES], \"reduce\": R"
                          f"[, \"threshold\": X]}}, got {spec!r}")
    of = spec.get("of")
    if not (isinstance(of, str) or (isinstance(of, list) and of and all(isinstance(o, str) for o in of))):
        raise MetricError(f"{where}.of: must be a variable name or a list of names")
    if spec.get("reduce") not in REDUCTIONS:
        raise MetricError(f"{where}.reduce: must be one of {', '.join(REDUCTIONS)}, got {spec.get('reduce')!r}")
    needs_threshold = spec["reduce"] == "settling_time"
    if needs_threshold != ("threshold" in spec):
        raise MetricError(f"{where}: 'threshold' goes with settling_time, and only with it")
    if needs_threshold and not (isinstance(spec["threshold"], (int, float)) and spec["threshold"] >= 0):
        raise MetricError(f"{where}.threshold: must be a number >= 0")


def signals_of(spec) -> list:
    return [spec["of"]] if isinstance(spec["of"], str) else list(spec["of"])


def signal(spec, series: dict) -> np.ndarray:
    names = signals_of(spec)
    if len(names) == 1:
        return series[names[0]]
    return np.sqrt(sum(series[n] * series[n] for n in names))


def reduce(spec, times: np.ndarray, series: dict) -> float:
    """The metric of one run from its outputs at the communication points."""
    x = signal(spec, series)
    r = spec["reduce"]
    if r == "initial":
        return float(x[0])
    if r == "final":
        return float(x[-1])
    if r == "max":
        return float(np.max(x))
    if r == "min":
        return float(np.min(x))
    if r == "mean":
        return float(np.mean(x))
    if r == "time_of_max":
        return float(times[int(np.argmax(x))])
    if r == "time_of_min":
        return float(times[int(np.argmin(x))])
    outside = np.nonzero(np.abs(x) > spec["threshold"])[0]  # settling_time
    if len(outside) == 0:
        return float(times[0])
    return float(times[outside[-1] + 1]) if outside[-1] + 1 < len(times) else float("nan")
