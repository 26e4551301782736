"""What must hold at the end of a system's run: outcome.json in its folder,

    {"description": "...",
     "checks": [{"name": "the platform at the target height",
                 "value": "world.platform.position[3]",  (component.variable, a Real output)
                 "minus": "world.load.position[3]",      (optional: a difference of two)
                 "frame": "controller.paddle",           (optional, instead of minus: see below)
                 "reference": 0.5 or "controller.target", (a number, or a parameter bound in the SSD)
                 "band": 0.001,                           (the largest |value - reference| allowed)
                 "from": 5.0}]}                           (s: checked at every communication point from then on)

With a `frame` P, the value NAME[i] is the i-th component of the vector NAME[1..3]
seen from the moving frame whose pose P.position[1..3] and P.orientation[1..4]
(w, x, y, z; body to world) are recorded: of R(q)^T (NAME - P.position), e.g. a ball's
height above a tilting paddle. The checks are evaluated on a run (masters.Run) and
described in plain words."""
import json
import pathlib
import re
from dataclasses import dataclass

import numpy as np

from systems import ssd


@dataclass(frozen=True)
class Check:
    name: str
    value: str
    reference: float | str
    band: float
    start: float = 0.0  # "from"
    minus: str | None = None
    frame: str | None = None

    def vector(self) -> tuple[str, int]:
        """NAME and i of a value NAME[i] (i from 1 to 3), which a frame needs."""
        m = re.fullmatch(r"(.+)\[([123])\]", self.value)
        if not m:
            raise ValueError(f"{self.name}: a value in a frame must be a vector's element NAME[1..3], got {self.value}")
        return m.group(1), int(m.group(2))

    def variables(self) -> list[str]:
        if self.frame:
            name, _ = self.vector()
            return ([f"{name}[{i}]" for i in (1, 2, 3)] + [f"{self.frame}.position[{i}]" for i in (1, 2, 3)]
                    + [f"{self.frame}.orientation[{i}]" for i in (1, 2, 3, 4)])
        return [self.value] + ([self.minus] if self.minus else [])

    def quantity(self) -> str:
        return self.value + (f" - {self.minus}" if self.minus else "") + (f" in {self.frame}'s frame"
                                                                           if self.frame else "")


@dataclass(frozen=True)
class Result:
    check: Check
    reference: float
    worst: float  # the largest |value - reference| over the window
    last: float  # the value at the last point
    holds: bool

    def describe(self) -> str:
        c = self.check
        source = f" ({c.reference})" if isinstance(c.reference, str) else ""
        return (f"{'holds' if self.holds else 'FAILS'}: {c.name}: {c.quantity()} within {c.band:g} of "
                f"{self.reference:g}{source} from {c.start:g} s on; largest deviation {self.worst:.3g}, "
                f"last value {self.last:.9g}")


@dataclass(frozen=True)
class Outcome:
    description: str
    checks: list[Check]

    def variables(self) -> list[str]:
        return sorted({v for c in self.checks for v in c.variables()})


def load(folder) -> Outcome:
    path = pathlib.Path(folder) / "outcome.json"
    data = json.loads(path.read_text())
    checks = []
    for i, c in enumerate(data.get("checks", [])):
        unknown = set(c) - {"name", "value", "minus", "frame", "reference", "band", "from"}
        missing = {"name", "value", "reference", "band"} - set(c)
        if unknown or missing or {"minus", "frame"} <= set(c):
            raise ValueError(f"{path}: checks[{i}]: " + (f"unknown fields {sorted(unknown)} " if unknown else "")
                             + (f"missing {sorted(missing)}" if missing else "")
                             + ("minus or frame, not both" if {"minus", "frame"} <= set(c) else ""))
        check = Check(c["name"], c["value"], c["reference"], float(c["band"]), float(c.get("from", 0.0)),
                      c.get("minus"), c.get("frame"))
        check.variables()  # a frame's value must name a vector's element
        checks.append(check)
    if not checks:
        raise ValueError(f"{path}: no checks")
    return Outcome(data.get("description", ""), checks)


def in_frame(check: Check, run) -> np.ndarray:
    """The checked component of R(q)^T (NAME - P.position) at each point."""
    name, i = check.vector()
    columns = check.variables()
    d = np.stack([run.col(v) for v in columns[0:3]], 1) - np.stack([run.col(v) for v in columns[3:6]], 1)
    w, x, y, z = (run.col(v) for v in columns[6:10])
    # column i of R(q), body to world: R^T d takes d into the frame
    axis = {1: (1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)),
            2: (2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)),
            3: (2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y))}[i]
    return sum(a * d[:, j] for j, a in enumerate(axis))


def evaluate(check: Check, run, system: ssd.System) -> Result:
    reference = system.parameter(check.reference) if isinstance(check.reference, str) else float(check.reference)
    if check.frame:
        value = in_frame(check, run)
    else:
        value = run.col(check.value) - (run.col(check.minus) if check.minus else 0.0)
    window = run.t >= check.start - 1e-9 * system.step
    if not window.any():
        raise ValueError(f"{check.name}: no communication point from {check.start} s on")
    deviation = np.abs(value[window] - reference)
    worst = float(np.max(deviation)) if np.all(np.isfinite(deviation)) else float("inf")
    return Result(check, reference, worst, float(value[-1]), worst <= check.band)


def evaluate_all(outcome: Outcome, run) -> list[Result]:
    return [evaluate(c, run, run.system) for c in outcome.checks]
