"""Report templates (scripts/reports/template.py): a template and its values match
exactly, so a report can have neither a hole nor a figure computed for nothing."""
import pytest
from reports.template import TemplateError, fields, fill, parts


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
    assert [p.stem for p in shipped] == ["accuracy", "stability"]
    for path in shipped:
        assert fields(path.read_text(encoding="utf-8")), path
