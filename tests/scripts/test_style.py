"""The code follows its own style files: every C and C++ file of the repository is as
clang-format (.clang-format) writes it, and the Python of python/, tests/ and scripts/
passes `ruff check` (pyproject.toml, [tool.ruff])."""
import importlib.util
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Where the C and C++ live: the core, the FMI adapters, the model description, the
# benchmarks and the tests (C++ units, the win64 importer).
CXX_FOLDERS = ["src", "fmu", "modelDescription", "bench", "tests"]


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
