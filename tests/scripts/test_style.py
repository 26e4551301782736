"""The code follows its own style files: the C++ listed in FORMATTED is as clang-format
(.clang-format) writes it. The list grows as files are formatted, each when it is next
edited for its own sake, so that a reformatting never hides in another change."""
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

# C++ files that follow .clang-format to the letter.
FORMATTED = [
    "fmu/instance.cpp",
    "fmu/instance.h",
    "src/collision_detection.cpp",
    "src/medium.cpp",
]


@pytest.mark.skipif(shutil.which("clang-format") is None,
                    reason="clang-format is not installed (scripts/setup.sh installs it)")
def test_formatted_cpp_files_follow_clang_format():
    files = [ROOT / f for f in FORMATTED]
    assert all(f.is_file() for f in files), [str(f) for f in files if not f.is_file()]
    run = subprocess.run(["clang-format", "--dry-run", "--Werror", "--style=file", *map(str, files)],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, "clang-format -i FILE would change:\n" + run.stderr[-4000:]
