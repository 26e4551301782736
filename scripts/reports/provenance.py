"""Which code a report measured: the commit, and whether the sources differed from it.
Every generated report names it, so that its figures can be traced to the code that
produced them, and a report made from a changed tree says so instead of passing for the
commit's."""
import subprocess

from rigidfmu.native import SOURCE_ROOT

# What a report's figures follow: the physics, the FMU, the benchmarks, the model
# description, the build, the command and the reports themselves.
SOURCES = ("src", "fmu", "bench", "modelDescription", "CMakeLists.txt", "python", "scripts/reports")


def source_state(root=SOURCE_ROOT):
    """'commit abc1234', '... with local changes to the sources', or why it is unknown."""
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"], check=True,
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--", *SOURCES],
                               check=True, capture_output=True, text=True).stdout.strip()
        return f"commit {head}" + (" with local changes to the sources" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown source state (no git)"
