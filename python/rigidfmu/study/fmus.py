"""The FMUs of a study: the given FMU, or one FMU per scene variant (the scene with a
run's sceneFields set), built by scripts/build_fmu.sh into OUT/fmus/ once; a rerun of
the study finds them there."""
import hashlib
import json
import os
import pathlib
import subprocess
from dataclasses import dataclass

from fmpy import read_model_description

from rigidfmu.native import SOURCE_ROOT
from rigidfmu.study.spec import StudyError, scene_variant

ROOT = SOURCE_ROOT  # the source tree: its build, scripts and docs


@dataclass
class StudyFmu:
    path: pathlib.Path
    guid: str
    key: str  # sha256 of the file: the workers' cache key
    variables: dict  # name -> fmpy ScalarVariable


def _describe(path: pathlib.Path) -> StudyFmu:
    md = read_model_description(str(path))
    return StudyFmu(path, md.guid, hashlib.sha256(path.read_bytes()).hexdigest(),
                    {v.name: v for v in md.modelVariables})


def prepare(study, variants: list, out: pathlib.Path, say=print) -> dict:
    """variant key -> StudyFmu for every scene variant the design uses."""
    if study.fmu is not None:
        fmu = _describe(study.fmu)
        return {key: fmu for key in variants}
    scene = json.loads(study.scene.read_text())
    cache = out / "fmus"
    cache.mkdir(parents=True, exist_ok=True)
    fmus = {}
    for key in variants:
        text = json.dumps(scene_variant(scene, json.loads(key)), indent=1, sort_keys=True)
        digest = hashlib.sha256(text.encode()).hexdigest()[:16]
        fmu = cache / f"{scene.get('name', 'scene')}-{digest}.fmu"
        if not fmu.exists():
            scene_file = cache / f"{fmu.stem}.json"
            scene_file.write_text(text)
            say(f"study: building {fmu.name} ({len(fmus) + 1} of {len(variants)} scene variants)")
            env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
            built = subprocess.run([str(ROOT / "scripts" / "build_fmu.sh"), str(scene_file), str(fmu)],
                                   env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if built.returncode != 0:
                raise StudyError(f"scene variant {key}: the FMU was not built:\n{built.stderr.strip()}")
        fmus[key] = _describe(fmu)
    return fmus


def check_names(study, fmus: dict):
    """Every name of the study is a variable of the FMU that can play its part."""
    variables = next(iter(fmus.values())).variables  # variants differ in values, not variables
    settable = lambda v: v.causality == "parameter" or v.initial == "exact"  # noqa: E731
    kinds = [("parameters", study.factors["parameters"], settable,
              "a parameter or an output with initial exact"),
             ("inputs", study.factors["inputs"], lambda v: v.causality == "input", "an input")]
    recorded = {n for spec in study.metrics.values()
                for n in ([spec["of"]] if isinstance(spec["of"], str) else spec["of"])}
    recorded |= set(study.trajectories)
    kinds.append(("metrics/trajectories", dict.fromkeys(recorded),
                  lambda v: v.type in ("Real", "Integer"), "a Real or Integer variable"))
    for section, names, ok, what in kinds:
        for name in names:
            v = variables.get(name)
            if v is None:
                raise StudyError(f"{section}: {name!r} is not a variable of the FMU")
            if not ok(v):
                raise StudyError(f"{section}: {name!r} is not {what}")
