"""A report names the code it measured (scripts/reports/provenance.py): the commit, and
'with local changes to the sources' when the sources differ from it; never the commit
alone for a changed tree."""
import subprocess

from reports.provenance import source_state


def git(root, *args):
    subprocess.run(["git", "-C", str(root), *args], check=True, capture_output=True, text=True)


def test_a_clean_tree_is_its_commit_and_a_changed_one_says_so(tmp_path):
    git(tmp_path, "init", "-q")
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "world.cpp").write_text("int x;\n")
    (tmp_path / "notes.txt").write_text("not a source\n")
    git(tmp_path, "add", "-A")
    git(tmp_path, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", "first")
    head = subprocess.run(["git", "-C", str(tmp_path), "rev-parse", "--short", "HEAD"], check=True,
                          capture_output=True, text=True).stdout.strip()
    assert source_state(tmp_path) == f"commit {head}"
    (tmp_path / "notes.txt").write_text("changed, but not a source\n")
    assert source_state(tmp_path) == f"commit {head}"
    (tmp_path / "src" / "world.cpp").write_text("int y;\n")
    assert source_state(tmp_path) == f"commit {head} with local changes to the sources"


def test_outside_a_checkout_the_state_is_unknown(tmp_path):
    assert source_state(tmp_path / "nowhere") == "unknown source state (no git)"
