"""What must hold at the end of a system's run: outcome.json in its folder,

    {"description": "...",
     "checks": [{"name": "the platform at the target height",
                 "value": "world.platform.position[3]",  (component.variable, a Real output)
                 "minus": "world.load.position[3]",      (optional: a difference of two)
                 "reference": 0.5 or "controller.target", (a number, or a parameter bound in the SSD)
                 "band": 0.001,                           (the largest |value - reference| allowed)
                 "from": 5.0}]}                           (s: checked at every communication point from then on)

and the same checks evaluated on a run (masters.Run), in plain words."""
import json
import pathlib
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

    def variables(self) -> list[str]:
        return [self.value] + ([self.minus] if self.minus else [])

    def quantity(self) -> str:
        return self.value + (f" - {self.minus}" if self.minus else "")


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
        unknown = set(c) - {"name", "value", "minus", "reference", "band", "from"}
        missing = {"name", "value", "reference", "band"} - set(c)
        if unknown or missing:
            raise ValueError(f"{path}: checks[{i}]: " + (f"unknown fields {sorted(unknown)} " if unknown else "")
                             + (f"missing {sorted(missing)}" if missing else ""))
        checks.append(Check(c["name"], c["value"], c["reference"], float(c["band"]), float(c.get("from", 0.0)),
                            c.get("minus")))
    if not checks:
        raise ValueError(f"{path}: no checks")
    return Outcome(data.get("description", ""), checks)


def evaluate(check: Check, run, system: ssd.System) -> Result:
    reference = system.parameter(check.reference) if isinstance(check.reference, str) else float(check.reference)
    value = run.col(check.value) - (run.col(check.minus) if check.minus else 0.0)
    window = run.t >= check.start - 1e-9 * system.step
    if not window.any():
        raise ValueError(f"{check.name}: no communication point from {check.start} s on")
    deviation = np.abs(value[window] - reference)
    worst = float(np.max(deviation)) if np.all(np.isfinite(deviation)) else float("inf")
    return Result(check, reference, worst, float(value[-1]), worst <= check.band)


def evaluate_all(outcome: Outcome, run) -> list[Result]:
    return [evaluate(c, run, run.system) for c in outcome.checks]
