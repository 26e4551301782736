"""The table of example FMUs (docs/reports/fmus.md): for each scene in scripts/scenes/, the FMU's
size, what its binaries weigh per platform (unpacked: linux64's library with the
libraries bundled beside it, win64's one DLL), its bundled libraries, its number of
variables and its cost per internal step (median of repeated runs through fmpy, 1 s
communication steps). Rewrites the part of docs/reports/fmus.md between the fmu-table
markers, or prints the table with --print.

usage: scripts/report.sh fmus [--print] [--quick] [--build BUILD_DIR]"""
import argparse
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import zipfile

from fmpy import read_model_description

from reports.fmu_timing import seconds_per_internal_step
from rigidfmu.native import SOURCE_ROOT

ROOT = SOURCE_ROOT  # the source tree: its build, scripts and docs
BEGIN, END = "<!-- fmu-table:begin -->", "<!-- fmu-table:end -->"


def table(build_dir, quick):
    seconds, repeats = (1, 1) if quick else (5, 5)
    rows = ["| scene | FMU size | linux64 binaries | win64 binary | bundled libraries (linux64) | variables "
            "| cost per step |",
            "|---|---:|---:|---:|---|---:|---:|"]
    with tempfile.TemporaryDirectory() as folder:
        for scene in sorted((ROOT / "scripts" / "scenes").glob("*.json")):
            fmu = pathlib.Path(folder, scene.stem + ".fmu")
            subprocess.run([str(ROOT / "scripts" / "build_fmu.sh"), str(scene), str(fmu)], check=True,
                           stdout=subprocess.DEVNULL,
                           env=dict(os.environ, RIGIDFMU_SKIP_SETUP="1", RIGIDFMU_BUILD=str(build_dir)))
            md = read_model_description(str(fmu))
            with zipfile.ZipFile(fmu) as z:
                libs = sorted(pathlib.Path(n).name for n in z.namelist()
                              if n.startswith("binaries/linux64/lib"))
                weight = {platform: sum(i.file_size for i in z.infolist()
                                        if i.filename.startswith(f"binaries/{platform}/"))
                          for platform in ("linux64", "win64")}
            us = seconds_per_internal_step(fmu, 0.5, seconds * 2, repeats) * 1e6
            win64 = f"{weight['win64'] / 1024:.0f} KiB" if weight["win64"] else "none"
            rows.append(f"| `{scene.name}` ({md.modelName}) | {fmu.stat().st_size / 1024:.0f} KiB | "
                        f"{weight['linux64'] / 1024:.0f} KiB | {win64} | "
                        f"{', '.join(libs) if libs else 'none'} | {len(md.modelVariables)} | {us:.2f} µs |")
    return "\n".join(rows)


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--print", action="store_true", help="print the table instead of updating docs/reports/fmus.md")
    p.add_argument("--quick", action="store_true", help="one short run per scene")
    p.add_argument("--build", default=os.environ.get("RIGIDFMU_BUILD", ROOT / "build"))
    args = p.parse_args(argv)
    text = table(pathlib.Path(args.build), args.quick)
    if args.print:
        print(text)
        return 0
    readme = ROOT / "docs" / "reports" / "fmus.md"
    old = readme.read_text()
    if BEGIN not in old or END not in old:
        print(f"{readme.relative_to(ROOT)} has no {BEGIN} ... {END} markers", file=sys.stderr)
        return 1
    new = re.sub(re.escape(BEGIN) + ".*?" + re.escape(END), lambda _: f"{BEGIN}\n{text}\n{END}", old,
                 flags=re.S)
    readme.write_text(new)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(prog="scripts/report.sh fmus"))
