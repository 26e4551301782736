"""Report prose lives in Markdown templates (scripts/reports/templates/NAME.md) with
{placeholders} for the figures and generated tables; the Python computes the values
only. A template and its values must match exactly: a placeholder without a value, or a
value no placeholder asks for, is an error rather than a report with a hole in it.

A paragraph that only some runs write (a section of a peer that was not measured, a
sentence that only a failed step calls for) is a part of the template: after the
report's own text, each part opens with a line `<!-- part NAME -->` (or
`<!-- part NAME: what it is for -->`), and the report fills the part it needs into a
placeholder of its text."""
import pathlib
import re
import string

FOLDER = pathlib.Path(__file__).resolve().parent / "templates"
PART = re.compile(r"^<!-- part (\w+)(?:: [^\n]*)? -->\n", re.M)


class TemplateError(ValueError):
    pass


def fields(text):
    """The placeholders of a template text, in order of first appearance."""
    seen = []
    for _, name, spec, conversion in string.Formatter().parse(text):
        if name is None:
            continue
        if not name.isidentifier() or spec or conversion:
            raise TemplateError(f"placeholder {{{name}}} must be a bare name")
        if name not in seen:
            seen.append(name)
    return seen


def parts(text):
    """{"": the report's text, NAME: each part}. A part is its lines up to the next part,
    without the blank lines around them; the report's text, when parts follow it, ends
    with one newline."""
    pieces = PART.split(text)
    out = {"": pieces[0] if len(pieces) == 1 else pieces[0].rstrip("\n") + "\n"}
    for name, body in zip(pieces[1::2], pieces[2::2]):
        if name in out:
            raise TemplateError(f"part {name} twice")
        out[name] = body.strip("\n")
    return out


def fill(name, values, folder=FOLDER, part=""):
    """The template `name` (templates/NAME.md), or one of its parts, with every
    placeholder replaced by its value (str() of it). Literal braces are written {{ and }}."""
    path = pathlib.Path(folder) / f"{name}.md"
    texts = parts(path.read_text(encoding="utf-8"))
    where = f"{path.name} (part {part})" if part else path.name
    if part not in texts:
        raise TemplateError(f"{path.name}: no part {part}")
    text = texts[part]
    wanted = fields(text)
    missing = [f for f in wanted if f not in values]
    unused = [k for k in values if k not in wanted]
    if missing or unused:
        raise TemplateError(f"{where}: no value for {missing}" if missing else
                            f"{where}: no placeholder for {unused}")
    return text.format_map({k: str(v) for k, v in values.items()})
