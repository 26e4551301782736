"""The code follows its own style files: every C and C++ file of the repository is as
clang-format (.clang-format) writes it, and the Python of python/, tests/ and scripts/
passes `ruff check` (pyproject.toml, [tool.ruff]); no function of the core, the FMU
adapter or the model description runs over 60 lines; commit subjects stay within 72
characters (CONTRIBUTING.md)."""
import importlib.util
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Where the C and C++ live: the core, the FMI adapters, the model description, the
# benchmarks, the tests (C++ units, the win64 importer) and the example systems' C FMUs
# (scripts/systems).
CXX_FOLDERS = ["src", "fmu", "modelDescription", "bench", "tests", "scripts"]


def cxx_files(folders=CXX_FOLDERS):
    return sorted(f for folder in folders for pattern in ("*.cpp", "*.h", "*.c")
                  for f in (ROOT / folder).rglob(pattern))


def test_every_cxx_folder_has_sources():
    # a moved folder would otherwise leave its files unchecked
    assert all(cxx_files([folder]) for folder in CXX_FOLDERS)


@pytest.mark.skipif(shutil.which("clang-format") is None,
                    reason="clang-format is not installed (scripts/setup.sh installs it)")
def test_formatted_cpp_files_follow_clang_format():
    files = cxx_files()
    run = subprocess.run(["clang-format", "--dry-run", "--Werror", "--style=file", *map(str, files)],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, "clang-format -i FILE would change:\n" + run.stderr[-4000:]


@pytest.mark.skipif(importlib.util.find_spec("ruff") is None,
                    reason="ruff is not installed (requirements.txt pins it; scripts/setup.sh installs it)")
def test_python_follows_ruff():
    run = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--output-format", "concise",
                          "python", "tests", "scripts"], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, "ruff check finds:\n" + run.stdout[-4000:] + run.stderr[-2000:]


# ---- function length and commit subjects (CONTRIBUTING.md) ----------------------------

MAX_FUNCTION_LINES = 60
# The last commit before the 72-character rule (CONTRIBUTING.md): its subject and older
# ones run longer.
SUBJECT_RULE_BASE = "9422247"
MAX_SUBJECT = 72


def top_level_functions(path: pathlib.Path):
    """(first line, line count) of each function body at namespace level in a C++ file:
    braces counted outside strings and comments; a block opened by namespace, extern,
    struct, class, enum or union is not a function (its members are)."""
    text = path.read_text(encoding="utf-8")
    # strings and comments in one pass (a "//" inside a string is no comment)
    token = re.compile(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'|//[^\n]*|/\*.*?\*/', re.S)
    text = token.sub(lambda m: '""' if m.group(0)[0] in "\"'" else re.sub(r"[^\n]", " ", m.group(0)), text)
    out, stack, statement, line = [], [], "", 1
    for ch in text:
        if ch == "\n":
            line += 1
        if ch == "{":
            head = statement.strip()
            scope = re.match(r"(template\s*<[^>]*>\s*)?(namespace|extern|struct|class|enum|union)\b", head)
            is_function = not stack or stack[-1][0] == "scope"
            stack.append(("scope" if scope else ("function" if is_function and "(" in head else "block"), line))
            statement = ""
        elif ch == "}":
            kind, first = stack.pop()
            if kind == "function" and (not stack or stack[-1][0] == "scope"):
                out.append((first, line - first + 1))
            statement = ""
        elif ch == ";":
            statement = ""
        else:
            statement += ch
    return out


def test_no_function_of_the_core_or_the_adapter_is_longer_than_60_lines():
    long = [f"{path.relative_to(ROOT)}:{first} ({count} lines)"
            for path in cxx_files(["src", "fmu", "modelDescription"])
            for first, count in top_level_functions(path) if count > MAX_FUNCTION_LINES]
    assert not long, "functions over 60 lines (split them into named stages):\n" + "\n".join(long)


def test_the_length_check_finds_a_long_function(tmp_path):
    source = tmp_path / "long.cpp"
    body = "\n".join("  x += 1;" for _ in range(70))
    source.write_text("namespace a {\nstruct S { int f() { return 1; } };\n"
                      f"int g(int x) {{\n{body}\n  return x;\n}}\n}}  // namespace a\n")
    assert top_level_functions(source) == [(2, 1), (3, 73)]


@pytest.mark.skipif(shutil.which("git") is None or not (ROOT / ".git").exists(), reason="not a git checkout")
def test_commit_subjects_are_at_most_72_characters():
    known = subprocess.run(["git", "cat-file", "-e", SUBJECT_RULE_BASE + "^{commit}"], cwd=ROOT).returncode == 0
    span = [f"{SUBJECT_RULE_BASE}..HEAD"] if known else ["-n", "200", "HEAD"]  # a shallow clone: what it has
    log = subprocess.run(["git", "log", "--format=%h %s", *span], capture_output=True, text=True, cwd=ROOT, check=True)
    long = [entry for entry in log.stdout.splitlines() if len(entry.split(" ", 1)[1]) > MAX_SUBJECT]
    assert not long, "commit subjects over 72 characters (CONTRIBUTING.md):\n" + "\n".join(long)
