"""The stability stress suite in quick mode (scripts/stress.sh --quick): every case with
every integration method of the FMU; it must write a table with a row for every case
and method, and no run may FAIL (a non-finite output or a broken criterion while the
FMU answered fmi2OK). No timing is asserted."""
import os
import pathlib
import re
import subprocess
import sys

import pytest
from fmpy import read_model_description
from reports import stability as stress  # the case list, to check the table against it

ROOT = pathlib.Path(__file__).resolve().parents[2]
LAB = os.pathsep.join(filter(None, [str(ROOT / "scripts"), os.environ.get("PYTHONPATH")]))  # scripts/reports

pytestmark = pytest.mark.slow  # a whole script or browser run (pyproject.toml)


def methods_of_the_fmu(fmu_of):
    fmu = fmu_of(stress.spinner_scene("Probe", (1, 2, 3), (0, 0, 1)))
    md = read_model_description(str(fmu))
    return [i.name for t in md.typeDefinitions if t.name == "SolverMethod" for i in t.items]


def test_quick_stress_suite_has_every_case_and_method_and_nothing_fails(tmp_path, fmu_of):
    methods = methods_of_the_fmu(fmu_of)  # builds the core if needed, as the suite would
    assert methods, "no SolverMethod enumeration"
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1", PYTHONPATH=LAB)  # as scripts/stress.sh
    proc = subprocess.run([sys.executable, "-m", "reports.stability", "--quick", "--out", str(tmp_path)],
                          capture_output=True, text=True, env=env, cwd=ROOT)
    table = tmp_path / "stability.md"
    assert table.exists(), proc.stdout[-3000:] + proc.stderr[-3000:]
    text = table.read_text()
    # no placeholder left unfilled in the prose (a plain string where an f-string was meant)
    placeholders = re.findall(r"\{[A-Za-z_]\w*\}", text)
    assert not placeholders, placeholders
    assert re.search(r"at (commit [0-9a-f]{7,}|unknown source state)", text)  # the code it measured
    rows = re.findall(r"^\| `([^`]+)` \| (\S+) \| ([^|]+?) \|", text.split("## Every run", 1)[1], re.M)
    seen = {(c, m): outcome for c, m, outcome in rows}
    keys = [c.key for c in stress.cases(True, [(m, i + 1, "") for i, m in enumerate(methods)])]
    missing = [(c, m) for c in keys for m in methods if (c, m) not in seen]
    assert not missing, f"runs missing from the table: {missing}"
    for outcome in seen.values():
        assert re.match(r"(holds|sub-stepped|refused|FAILS)\b", outcome), outcome
    summary = text.split("## Summary", 1)[1].split("## Every run", 1)[0]
    for c in keys:
        assert re.search(rf"^\| `{re.escape(c)}` \|", summary, re.M), f"{c} not in the summary"
    failing = [line[:400] for line in text.split("## Every run", 1)[1].splitlines()
               if re.match(r"^\| `[^`]+` \| \S+ \| FAILS", line)]
    assert not failing, "runs that FAIL:\n" + "\n".join(failing)
    # the suite's own verdict: it exits non-zero exactly when some run FAILS
    assert (proc.returncode != 0) == ("FAILS" in summary), proc.stdout[-3000:] + proc.stderr[-3000:]
