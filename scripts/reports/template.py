"""Report prose lives in Markdown templates (scripts/reports/templates/NAME.md) with
{placeholders} for the figures and generated tables; the Python computes the values
only. A template and its values must match exactly: a placeholder without a value, or a
value no placeholder asks for, is an error rather than a report with a hole in it."""
import pathlib
import string

FOLDER = pathlib.Path(__file__).resolve().parent / "templates"


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


def fill(name, values, folder=FOLDER):
    """The template `name` (templates/NAME.md) with every placeholder replaced by its value
    (str() of it). Literal braces are written {{ and }}."""
    path = pathlib.Path(folder) / f"{name}.md"
    text = path.read_text(encoding="utf-8")
    wanted = fields(text)
    missing = [f for f in wanted if f not in values]
    unused = [k for k in values if k not in wanted]
    if missing or unused:
        raise TemplateError(f"{path.name}: no value for {missing}" if missing else
                            f"{path.name}: no placeholder for {unused}")
    return text.format_map({k: str(v) for k, v in values.items()})
