"""A study file: reading and checking it, and its design (the list of runs).

The format is documented in README.md, "## Studies", and in `rigidfmu study --help`. Every
rule is checked here, before anything is built or run, with a message that names the
field, so that a misspelt key does not silently run a different study.
"""
import copy
import hashlib
import itertools
import json
import pathlib
import re
import tomllib
from dataclasses import dataclass, field

import numpy as np

from rigidfmu.errors import StudyError  # noqa: F401 (the study's errors, by this name too)
from rigidfmu.study.metrics import check_metric

SECTIONS = ("parameters", "sceneFields", "inputs")
TOP_KEYS = {"scene", "fmu", "stopTime", "stepSize", "design", *SECTIONS, "metrics",
            "trajectories"}
DISTRIBUTIONS = {"uniform", "normal", "loguniform"}


@dataclass
class Study:
    path: pathlib.Path
    name: str
    scene: pathlib.Path | None  # exactly one of scene and fmu
    fmu: pathlib.Path | None
    stop_time: float
    step_size: float
    design: dict
    factors: dict  # section -> {name: spec}, in file order
    metrics: dict
    trajectories: list


@dataclass
class Run:
    index: int  # position in the design
    parameters: dict = field(default_factory=dict)  # FMU variable -> number (set through FMI)
    scene_fields: dict = field(default_factory=dict)  # scene path -> value (one FMU per variant)
    inputs: dict = field(default_factory=dict)  # FMU input -> number or [[t, v], ...]
    variant: str = ""  # key of the FMU this run uses
    run_id: str = ""


def load(path) -> Study:
    path = pathlib.Path(path).resolve()
    text = path.read_bytes()
    try:
        raw = tomllib.loads(text.decode()) if path.suffix == ".toml" else json.loads(text)
    except (ValueError, tomllib.TOMLDecodeError) as e:
        raise StudyError(f"{path}: not valid {path.suffix[1:].upper() or 'JSON'}: {e}") from e
    if not isinstance(raw, dict):
        raise StudyError(f"{path}: the study must be an object")
    unknown = set(raw) - TOP_KEYS
    if unknown:
        raise StudyError(f"unknown field(s) {sorted(unknown)}; known: {sorted(TOP_KEYS)}")
    if ("scene" in raw) == ("fmu" in raw):
        raise StudyError("give exactly one of 'scene' (a scene file) and 'fmu' (an FMU file)")
    target = path.parent / (raw.get("scene") or raw.get("fmu"))
    if not target.is_file():
        raise StudyError(f"{'scene' if 'scene' in raw else 'fmu'}: no file {target}")
    stop, step = _positive(raw, "stopTime"), _positive(raw, "stepSize")
    if abs(stop / step - round(stop / step)) > 1e-9 * (stop / step):
        raise StudyError(f"stopTime ({stop}) must be a whole number of stepSize ({step})")
    factors = {s: dict(raw.get(s, {})) for s in SECTIONS}
    if factors["sceneFields"] and "fmu" in raw:
        raise StudyError("sceneFields need a 'scene' (each scene variant is built to its own FMU)")
    design = _check_design(raw.get("design", {"type": "grid"}))
    for section, entries in factors.items():
        for name, spec in entries.items():
            _check_spec(f"{section}.{name}", spec, design["type"], section == "inputs")
        if section == "sceneFields":
            for name in entries:
                parse_scene_path(name)
    metrics = raw.get("metrics", {})
    if not isinstance(metrics, dict):
        raise StudyError("metrics: must be an object of name: {of, reduce}")
    for name, spec in metrics.items():
        check_metric(name, spec)
    trajectories = raw.get("trajectories", [])
    if not (isinstance(trajectories, list) and all(isinstance(t, str) for t in trajectories)):
        raise StudyError("trajectories: must be a list of variable names")
    return Study(path, path.stem, target if "scene" in raw else None,
                 target if "fmu" in raw else None, stop, step, design, factors, metrics,
                 trajectories)


def _positive(raw, key):
    value = raw.get(key)
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not value > 0:
        raise StudyError(f"{key}: must be a number > 0, got {value!r}")
    return float(value)


def _check_design(design):
    kind = design.get("type") if isinstance(design, dict) else None
    if kind == "grid" and set(design) == {"type"}:
        return design
    if kind == "random" and set(design) <= {"type", "runs", "seed"}:
        runs, seed = design.get("runs"), design.get("seed", 0)
        if not (isinstance(runs, int) and runs > 0 and isinstance(seed, int) and seed >= 0):
            raise StudyError("design: random needs 'runs' (integer > 0) and an optional 'seed' (integer >= 0)")
        return {"type": "random", "runs": runs, "seed": seed}
    raise StudyError(f"design: must be {{\"type\": \"grid\"}} or "
                     f"{{\"type\": \"random\", \"runs\": N, \"seed\": S}}, got {design!r}")


def _check_spec(where, spec, design, is_input):
    if not isinstance(spec, dict):
        _check_value(where, spec, is_input)
        return
    if len(spec) != 1:
        raise StudyError(f"{where}: a varied value has one key: values, {', '.join(sorted(DISTRIBUTIONS))}")
    (kind, arg), = spec.items()
    if kind == "values":
        if not (isinstance(arg, list) and arg):
            raise StudyError(f"{where}: values must be a non-empty list")
        for v in arg:
            _check_value(where, v, is_input)
    elif kind in DISTRIBUTIONS:
        if design != "random":
            raise StudyError(f"{where}: '{kind}' needs design type random (a grid takes 'values')")
        if not (isinstance(arg, list) and len(arg) == 2 and all(_is_number(a) for a in arg)):
            raise StudyError(f"{where}: {kind} takes [a, b], two numbers")
        if kind == "normal" and not arg[1] >= 0:
            raise StudyError(f"{where}: normal takes [mean, sd >= 0]")
        if kind == "loguniform" and not 0 < arg[0] <= arg[1]:
            raise StudyError(f"{where}: loguniform takes [low, high], 0 < low <= high")
        if kind == "uniform" and not arg[0] <= arg[1]:
            raise StudyError(f"{where}: uniform takes [low, high], low <= high")
    else:
        raise StudyError(f"{where}: unknown kind '{kind}'; use values, {', '.join(sorted(DISTRIBUTIONS))}")


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v)


def _check_value(where, value, is_input):
    if _is_number(value):
        return
    if is_input and isinstance(value, list) and value and all(
            isinstance(r, list) and len(r) == 2 and all(_is_number(x) for x in r) for r in value):
        times = [r[0] for r in value]
        if times != sorted(times):
            raise StudyError(f"{where}: a table's times must be increasing")
        return
    what = "a number or a table [[t, v], ...]" if is_input else "a number"
    raise StudyError(f"{where}: must be {what}, got {value!r}")


# ---- design ---------------------------------------------------------------------------

def design_runs(study: Study) -> list[Run]:
    """The runs of the design, in a fixed order: the grid in file order (the last
    factor varies fastest), or `runs` random draws from numpy's PCG64 seeded with
    `seed`, one factor after the other in file order."""
    factors = [(s, n, spec) for s in SECTIONS for n, spec in study.factors[s].items()]
    if study.design["type"] == "grid":
        axes = [spec["values"] if isinstance(spec, dict) else [spec] for _, _, spec in factors]
        combos = list(itertools.product(*axes))
    else:
        count = study.design["runs"]
        rng = np.random.default_rng(study.design["seed"])
        columns = [_draw(rng, spec, count) for _, _, spec in factors]
        combos = list(zip(*columns)) if columns else [()] * count
    runs = []
    for i, combo in enumerate(combos):
        run = Run(i)
        for (section, name, _), value in zip(factors, combo):
            {"parameters": run.parameters, "sceneFields": run.scene_fields,
             "inputs": run.inputs}[section][name] = value
        runs.append(run)
    return runs


def _draw(rng, spec, count):
    if not isinstance(spec, dict):
        return [spec] * count
    (kind, arg), = spec.items()
    if kind == "values":
        return [arg[i] for i in rng.integers(0, len(arg), size=count)]
    if kind == "uniform":
        return [float(x) for x in rng.uniform(arg[0], arg[1], size=count)]
    if kind == "normal":
        return [float(x) for x in rng.normal(arg[0], arg[1], size=count)]
    return [float(x) for x in np.exp(rng.uniform(np.log(arg[0]), np.log(arg[1]), size=count))]


def variant_key(scene_fields: dict) -> str:
    return json.dumps(scene_fields, sort_keys=True)


def run_identity(run: Run, guid: str, study: Study) -> str:
    """A run's identity: its full set of values, the FMU's GUID (the scene's content),
    the experiment and what is recorded. A rerun skips the runs whose identity has a
    result already; changing any of these makes a run new."""
    key = {"guid": guid, "parameters": run.parameters, "sceneFields": run.scene_fields,
           "inputs": run.inputs, "stopTime": study.stop_time, "stepSize": study.step_size,
           "metrics": study.metrics, "trajectories": study.trajectories}
    # json writes floats by repr, which round-trips: equal text <=> bitwise equal values
    return hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:20]


# ---- scene fields ---------------------------------------------------------------------

_STEP = re.compile(r"([A-Za-z_]\w*)((?:\[[^\]]+\])*)")


def parse_scene_path(path: str) -> list:
    """'bodies[slider].kineticFriction' -> ['bodies', 'slider'(by name), 'kineticFriction'].
    A bracket holds a 0-based list index (as in the scene checker's messages) or the
    `name` of a list element."""
    steps = []
    for part in path.split("."):
        m = _STEP.fullmatch(part)
        if not m:
            raise StudyError(f"sceneFields.{path}: not a scene path like bodies[slider].kineticFriction")
        steps.append(m.group(1))
        for sub in re.findall(r"\[([^\]]+)\]", m.group(2)):
            steps.append(int(sub) if sub.isdigit() else ("name", sub))
    return steps


def scene_variant(scene: dict, scene_fields: dict) -> dict:
    """A copy of the scene with the fields set. The scene checker (at build) refuses
    what is not a scene field or breaks a rule."""
    out = copy.deepcopy(scene)
    for path, value in scene_fields.items():
        node, steps = out, parse_scene_path(path)
        for step in steps[:-1]:
            node = _child(node, step, path)
        last = steps[-1]
        if isinstance(last, str) and isinstance(node, dict):
            node[last] = value
        elif isinstance(last, int) and isinstance(node, list) and last < len(node):
            node[last] = value
        else:
            raise StudyError(f"sceneFields.{path}: cannot set {last!r} there")
    return out


def _child(node, step, path):
    if isinstance(step, tuple):  # a list element by name
        hits = [e for e in node if isinstance(e, dict) and e.get("name") == step[1]] \
            if isinstance(node, list) else []
        if len(hits) != 1:
            raise StudyError(f"sceneFields.{path}: no single element named {step[1]!r}")
        return hits[0]
    try:
        return node[step]
    except (KeyError, IndexError, TypeError):
        raise StudyError(f"sceneFields.{path}: the scene has no {step!r} there") from None
