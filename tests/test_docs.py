"""The documentation stays inside the repository and the README stays a short guide:
README ≤ 12 KB, every link of the README and of docs/ resolves to a file (and, for
#anchors into Markdown, a heading) in this repository, and docs/scene-format.md keeps
every name the public contract (INTERFACE.md, beside the repository) fixes."""
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", *sorted((ROOT / "docs").rglob("*.md"))]
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"```.*?```", re.S)


def links(md: pathlib.Path):
    text = FENCE.sub("", md.read_text(encoding="utf-8"))
    return LINK.findall(text)


def anchors(md: pathlib.Path):
    """GitHub's heading anchors: lower case, punctuation dropped, spaces to hyphens."""
    out = set()
    for line in FENCE.sub("", md.read_text(encoding="utf-8")).splitlines():
        m = re.match(r"#+\s+(.*)", line)
        if m:
            title = re.sub(r"[^\w\- ]", "", m.group(1).strip().lower())
            out.add(title.replace(" ", "-"))
    return out


def test_readme_is_at_most_12_kb():
    size = (ROOT / "README.md").stat().st_size
    assert size <= 12 * 1024, f"README.md is {size} bytes, the limit is {12 * 1024}"


@pytest.mark.parametrize("md", DOCS, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_link_resolves_inside_the_repository(md):
    broken = []
    for target in links(md):
        if re.match(r"[a-z]+:", target):
            broken.append(f"{target}: points outside the repository")
            continue
        path, _, anchor = target.partition("#")
        file = (md.parent / path).resolve() if path else md
        if ROOT not in file.parents and file != ROOT:
            broken.append(f"{target}: resolves outside the repository")
        elif not file.exists():
            broken.append(f"{target}: no such file")
        elif anchor and file.suffix == ".md" and anchor not in anchors(file):
            broken.append(f"{target}: no heading #{anchor} in {file.relative_to(ROOT)}")
    assert not broken, f"{md.relative_to(ROOT)}:\n  " + "\n  ".join(broken)


def test_docs_name_no_file_outside_the_repository():
    for md in DOCS:
        text = md.read_text(encoding="utf-8")
        assert "../shared" not in text and "shared/INTERFACE" not in text, md


def contract_names(text: str):
    """The scene fields and variable names INTERFACE.md fixes: every `code` span that is
    a name (letters, digits, dots, brackets, underscores), with <placeholders> kept."""
    spans = re.findall(r"`([^`\n]+)`", FENCE.sub("", text))
    names = {s for s in spans if re.fullmatch(r"[A-Za-z_<>][\w.<>\[\]]*", s)}
    for block in re.findall(r"```json(.*?)```", text, re.S):
        names |= set(re.findall(r'"([A-Za-z_]\w*)"\s*:', block))
    return names


def test_scene_format_holds_every_name_of_the_contract():
    interface = ROOT.parent / "shared" / "INTERFACE.md"
    if not interface.exists():
        pytest.skip(f"{interface} is not beside this checkout")
    fixed = contract_names(interface.read_text(encoding="utf-8"))
    assert len(fixed) > 30, "the contract's names were not found: has its format changed?"
    ours = (ROOT / "docs" / "scene-format.md").read_text(encoding="utf-8")
    missing = sorted(n for n in fixed if n not in ours)
    assert not missing, f"docs/scene-format.md lacks names the contract fixes: {missing}"


PATH_IN_CODE = re.compile(r"(?<![\w/.$])((?:scripts|python|tests|src|fmu|modelDescription|bench|docs|\.ci)/[\w./-]*\w)")


@pytest.mark.parametrize("md", DOCS, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_path_named_in_code_exists(md):
    """A file or folder of this repository named in a `code` span or a code block
    exists: a moved script does not leave the guide pointing at its old place."""
    text = md.read_text(encoding="utf-8")
    code = " ".join(re.findall(r"`([^`]+)`", FENCE.sub("", text)) + re.findall(r"```(.*?)```", text, re.S))

    def exists(p):  # `src/sleep.*` names src/sleep.h and src/sleep.cpp
        return (ROOT / p).exists() or any(ROOT.glob(p + ".*"))

    def generated(p):  # written by the commands themselves: build trees, results, figures
        return p.startswith(("build", "out/")) or (p.startswith("docs/reports/")
                                                   and p.endswith((".png", ".csv", ".parquet")))

    missing = sorted({p for p in PATH_IN_CODE.findall(code) if not exists(p) and not generated(p)})
    assert not missing, f"{md.relative_to(ROOT)} names paths that do not exist: {missing}"
