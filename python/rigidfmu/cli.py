"""The `rigidfmu` command: build, check and simulate scenes, replay runs and run
parameter studies. (The reports are made from the source tree: scripts/report.sh.)

Conventions as fmpy's command line: results on stdout (the files written), messages
on stderr, exit status 0 on success, 1 when the work failed (a refused scene, a
failed simulation), 2 for a wrong command line.
"""
import argparse
import pathlib
import sys

# the commands import what they use: `rigidfmu build` needs neither fmpy nor numpy
from rigidfmu import __version__, fmu_package, native
from rigidfmu.errors import RigidfmuError

EXIT_FAILED = 1


def fail(message: str) -> int:
    print(f"rigidfmu: {message}", file=sys.stderr)
    return EXIT_FAILED


def existing_file(text: str) -> pathlib.Path:
    path = pathlib.Path(text)
    if not path.is_file():
        raise argparse.ArgumentTypeError(f"no such file: {text}")
    return path.resolve()


def build_scene(scene: pathlib.Path, out: pathlib.Path, build_core: bool = True, win64: bool = True,
                fmi: int = 2) -> pathlib.Path:
    core = native.find(build=build_core, win64=win64)
    bundled = fmu_package.package(scene, out, core, fmi)
    platforms = "linux64" + (", win64" if core.win64 else "")
    print(f"rigidfmu: {scene.name} -> {out} ({platforms})" + (f", bundled: {', '.join(bundled)}" if bundled else ""),
          file=sys.stderr)
    if win64 and not core.win64:
        print("rigidfmu: no win64 binary: this installation or build tree has none "
              "(scripts/build_win64.sh cross-compiles them with MinGW-w64)", file=sys.stderr)
    return out


def cmd_build(args) -> int:
    out = (args.output or pathlib.Path(args.scene.stem + ".fmu")).resolve()
    build_scene(args.scene, out, build_core=not args.no_build, win64=not args.no_win64, fmi=args.fmi)
    print(out)
    return 0


def cmd_check(args) -> int:
    described = fmu_package.describe(args.scene, native.find(win64=False))
    print(f"{args.scene}: the scene is valid (model {described.model_identifier}, modules {described.modules})")
    for frame in described.frames:  # where to find a mesh file's origin, for placing the part
        print(f"  {frame}")
    return 0


def cmd_simulate(args) -> int:
    from rigidfmu import replay, simulate

    out_dir = args.out.resolve()
    target = args.target
    if target.suffix == ".json":
        target = build_scene(target, out_dir / f"{target.stem}.fmu", win64=not args.no_win64)
    files = simulate.simulate(target, out_dir, args.stop_time, args.output_interval, plot=args.plot)
    if args.replay:
        files.append(replay.write_fmu_replay(files[0], target, out_dir / f"{target.stem}.html"))
    for f in files:
        print(f)
    return 0


def cmd_replay(args) -> int:
    from rigidfmu import replay

    out = args.output or args.csv.with_suffix(".html")
    print(replay.write_replay(args.csv, args.scene, out))
    return 0


# The study's own dependencies, pyproject.toml's "study" extra: `pip install rigidfmu`
# leaves them out, so the command names the install that brings them instead of failing
# with an ImportError, or only once the runs start (dask and distributed are imported
# when the cluster is reached).
STUDY_MODULES = ("dask", "distributed", "pandas", "pyarrow", "tqdm")
STUDY_INSTALL = "pip install 'rigidfmu[study]'"


def cmd_study(args) -> int:
    import importlib.util

    missing = [m for m in STUDY_MODULES if importlib.util.find_spec(m) is None]
    if missing:
        return fail(f"study: needs {', '.join(missing)}, not installed: {STUDY_INSTALL}")
    try:
        from rigidfmu.study import run
    except ModuleNotFoundError as e:  # installed, but incompletely (a submodule or one of theirs)
        return fail(f"study: cannot import {e.name}: {STUDY_INSTALL}")
    return run.main(args.args, prog="rigidfmu study") or 0


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rigidfmu", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version=f"rigidfmu {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    b = sub.add_parser("build", help="build the FMU of a scene",
                       description="Builds the FMI 2.0 Co-Simulation FMU of one scene: its variables, and "
                                   "only the physics modules and libraries the scene uses.")
    b.add_argument("scene", type=existing_file, metavar="SCENE", help="scene file (JSON, docs/scene-format.md)")
    b.add_argument("-o", "--output", type=pathlib.Path, metavar="OUT.fmu",
                   help="the FMU to write (default: the scene's file name with .fmu, here)")
    b.add_argument("--no-build", action="store_true",
                   help="in the source tree, package from the build tree as it is (no CMake build first)")
    b.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                   help="FMI version of the FMU: 2 (FMI 2.0, the default) or 3 (FMI 3.0 Co-Simulation)")
    b.add_argument("--no-win64", action="store_true",
                   help="leave out binaries/win64 (by default the FMU carries linux64 and win64 binaries)")
    b.set_defaults(run=cmd_build)

    c = sub.add_parser("check", help="check a scene against the scene format's rules",
                       description="Checks a scene file; a broken rule is reported with the field it concerns "
                                   "and the limit, and exit status 1.")
    c.add_argument("scene", type=existing_file, metavar="SCENE")
    c.set_defaults(run=cmd_check)

    s = sub.add_parser("simulate", help="simulate an FMU (or a scene, built first) with fmpy",
                       description="Simulates with fmpy from 0 to the stop time and writes OUT/<name>.csv; "
                                   "--plot adds the PNG figures, --replay the 3D replay page.")
    s.add_argument("target", type=existing_file, metavar="FMU|SCENE", help="an FMU, or a scene file (.json)")
    s.add_argument("--stop-time", type=float, default=5.0, help="s (default 5)")
    s.add_argument("--output-interval", type=float, default=0.01, help="s between output rows (default 0.01)")
    s.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out"), help="folder for the results (default out)")
    s.add_argument("--plot", action="store_true", help="write the run's figures (PNG)")
    s.add_argument("--replay", action="store_true", help="write the run's 3D replay (self-contained HTML)")
    s.add_argument("--no-win64", action="store_true", help="a scene's FMU without binaries/win64 (see build)")
    s.set_defaults(run=cmd_simulate)

    r = sub.add_parser("replay", help="the 3D replay page of a run",
                       description="Writes one self-contained HTML file (three.js inlined) that replays a "
                                   "result CSV of the scene in any browser, offline.")
    r.add_argument("csv", type=existing_file, metavar="RESULT.csv")
    r.add_argument("scene", type=existing_file, metavar="SCENE")
    r.add_argument("-o", "--output", type=pathlib.Path, metavar="OUT.html", help="default: the CSV's name with .html")
    r.set_defaults(run=cmd_replay)

    st = sub.add_parser("study", help="run a parameter study of an FMU on Dask", add_help=False,
                        description="Runs a study file's runs on Dask; `rigidfmu study --help` gives the format.")
    st.add_argument("args", nargs=argparse.REMAINDER, metavar="STUDY [...]")
    st.set_defaults(run=cmd_study)
    return p


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["study"]:  # all of it is the study's command line, --help too
        args = argparse.Namespace(run=cmd_study, args=argv[1:])
    else:
        args = parser().parse_args(argv)
    try:
        return args.run(args)
    except RigidfmuError as e:
        return fail(str(e))
    except KeyboardInterrupt:
        return fail("interrupted")
