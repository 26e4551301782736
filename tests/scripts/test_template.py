"""Report templates (scripts/reports/template.py): a template and its values match
exactly, so a report can have neither a hole nor a figure computed for nothing. The
performance report is rendered here from the figures its last run saved
(docs/reports/performance/bench.json), as it is a pure function of them: running it
takes minutes of benchmarks."""
import copy
import pathlib
import re

import pytest
from reports import performance, template
from reports.template import TemplateError, fields, fill, parts

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAVED = ROOT / "docs" / "reports" / "performance" / "bench.json"
NUMBER = re.compile(r"\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def write(tmp_path, text):
    (tmp_path / "t.md").write_text(text, encoding="utf-8")


def test_a_template_is_filled_with_its_values(tmp_path):
    write(tmp_path, "# {title}\n\n{count} runs, {count} again; braces {{kept}}.\n")
    assert fill("t", {"title": "Stability", "count": 3}, folder=tmp_path) == \
        "# Stability\n\n3 runs, 3 again; braces {kept}.\n"


def test_a_missing_or_unused_value_is_refused(tmp_path):
    write(tmp_path, "{a} and {b}\n")
    with pytest.raises(TemplateError, match=r"no value for \['b'\]"):
        fill("t", {"a": 1}, folder=tmp_path)
    with pytest.raises(TemplateError, match=r"no placeholder for \['c'\]"):
        fill("t", {"a": 1, "b": 2, "c": 3}, folder=tmp_path)


def test_placeholders_are_bare_names():
    assert fields("{x} {y} {x}") == ["x", "y"]
    for bad in ("{x:.3f}", "{x!r}", "{x.y}", "{0}"):
        with pytest.raises(TemplateError):
            fields(bad)


def test_a_part_is_filled_on_its_own(tmp_path):
    write(tmp_path, "# {title}\n\n{note}\n\n<!-- part failed: a step failed -->\n"
                    "A step failed at {t} s.\n\n<!-- part quiet -->\nNothing to say.\n")
    note = fill("t", {"t": 0.5}, folder=tmp_path, part="failed")
    assert note == "A step failed at 0.5 s."
    assert fill("t", {}, folder=tmp_path, part="quiet") == "Nothing to say."
    # the report's own text asks for its values only, and ends with one newline
    assert fill("t", {"title": "Piles", "note": note}, folder=tmp_path) == "# Piles\n\nA step failed at 0.5 s.\n"
    with pytest.raises(TemplateError, match=r"\(part failed\): no value for \['t'\]"):
        fill("t", {}, folder=tmp_path, part="failed")
    with pytest.raises(TemplateError, match="no part missing"):
        fill("t", {}, folder=tmp_path, part="missing")


def test_a_part_is_named_once():
    with pytest.raises(TemplateError, match="part a twice"):
        parts("text\n<!-- part a -->\none\n<!-- part a -->\ntwo\n")
    assert parts("no parts\n\n") == {"": "no parts\n\n"}


def test_every_shipped_template_parses():
    # (each report's test fills its template: a missing or unused value fails it there)
    from reports import template
    shipped = sorted(template.FOLDER.glob("*.md"))
    assert [p.stem for p in shipped] == ["accuracy", "performance", "stability"]
    for path in shipped:
        assert fields(path.read_text(encoding="utf-8")), path


@pytest.fixture
def saved():
    return performance.load_report(SAVED)


def test_the_performance_report_renders_every_saved_figure(saved):
    text = performance.render(saved)
    assert not re.search(r"\{\w+\}|<!-- part", text)  # no placeholder nor part marker left
    # the committed report was written from these figures: the same numbers in the same
    # order (the prose may change; a figure may not go missing)
    committed = (ROOT / "docs" / "reports" / "performance.md").read_text(encoding="utf-8")
    assert NUMBER.findall(text) == NUMBER.findall(committed)
    for label, value, status in saved["targets"] + saved["windows_targets"] + saved["windows_checks"]:
        assert f"| {label} | {value} | **{status}** |" in text
    for n, pile in saved["piles"].items():
        assert f"| {n} | {pile['broadphase']:.1f} |" in text and f"**{pile['total_us']:.1f}**" in text
    for method, points in saved["free"].items():
        assert f"| `{method}` | " + " | ".join(f"{v:.1f}" for v in points.values()) + " |" in text
    for n, m in saved["windows"].items():
        assert f"| {n} | {m['fall']['us_per_step']:.1f} µs | {performance.fmt_s(m['fall']['s_per_simulated_s'])} |" \
            in text
    assert f"Median ratio: **{saved['interleaved']['ratio']:.2f}**, on which the target is judged." in text
    assert saved["meta"]["source"] in text.splitlines()[2]


def without_mujoco(r):
    r.update(peers=None, interleaved=None, windows_interleaved=None)
    r["accuracy"].update(mujoco=[], equal_accuracy=[])
    r["chain"].update(mujoco=None, ratio=None, ratio_rk4=None, rounds=[])
    r["meshes"]["pile"].update(mujoco=None, ratio_fall=None, ratio_rest=None)


def quick(r):
    r["meta"]["quick"], r["windows_wide"] = True, {}
    for key in ("piles", "windows", "windows_awake"):
        r[key].pop(1000)
    r["interleaved"]["n"] = r["windows_interleaved"]["n"] = 100


def a_step_failed(r):
    r["piles"][100]["steps_ok"] -= 1
    r["windows"][1000]["steps_ok"] -= 1


def test_every_part_of_the_performance_template_is_written_by_some_run(saved, monkeypatch):
    written = set()
    fill_part = template.fill

    def recording(name, values, folder=template.FOLDER, part=""):
        written.add(part)
        return fill_part(name, values, folder, part)
    monkeypatch.setattr(template, "fill", recording)
    texts = {}
    for name, change in (("full", None), ("without MuJoCo", without_mujoco), ("quick", quick),
                         ("a step failed", a_step_failed)):
        r = copy.deepcopy(saved)
        if change:
            change(r)
        texts[name] = performance.render(r)
        assert not re.search(r"\{\w+\}|<!-- part", texts[name]), name
    assert written == set(parts((template.FOLDER / "performance.md").read_text(encoding="utf-8")))
    assert texts["without MuJoCo"].count("MuJoCo was not measured in this run") == 3
    assert "| MuJoCo | not measured | not measured |" in texts["without MuJoCo"]  # the pile of pebbles
    assert "| 1000 | not measured | not measured |" in texts["without MuJoCo"]
    assert "**Equal height**" not in texts["quick"] and "the full run times the pile of 1000 so" in texts["quick"]
    assert "A step failed in the piles of [100]: their times" in texts["a step failed"]
    assert "A step failed in the piles of [1000]: their windows" in texts["a step failed"]
