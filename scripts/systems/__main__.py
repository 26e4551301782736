"""python -m systems SYSTEM_FOLDER [--master libcosim|fmpy|both] [--out DIR]: what
scripts/system.sh runs. Builds the system's FMUs into DIR (default out/systems/NAME),
runs it, writes each master's recording (DIR/MASTER.csv), prints the outcome and exits
0 only when it holds (with both masters: in both, and their recordings equal to the bit);
1 when it does not or the run fails, 2 for a wrong command line."""
import argparse
import pathlib
import sys

import numpy as np

from systems import fmus, masters, outcome, ssd

ROOT = pathlib.Path(__file__).resolve().parents[2]
def report(run: masters.Run, results: list[outcome.Result]) -> None:
    s = run.system
    print(f"{s.name} in {run.master}: {s.steps} steps of {s.step:g} s to {s.stop:g} s, "
          f"{len(run.names)} variables recorded, {run.seconds:.2f} s")
    for r in results:
        print(f"  {r.describe()}")


def write_csv(run: masters.Run, path: pathlib.Path) -> None:
    np.savetxt(path, np.column_stack([run.t, run.values]), delimiter=",", fmt="%.17g",
               header=",".join(["time", *run.names]), comments="")


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="scripts/system.sh", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("system", type=pathlib.Path, metavar="SYSTEM_FOLDER", help="e.g. scripts/systems/lift")
    p.add_argument("--master", choices=("libcosim", "fmpy", "both"), default="libcosim",
                   help="the co-simulation master (default libcosim); both: each, and compared")
    p.add_argument("--out", type=pathlib.Path, help="folder for the FMUs and recordings (default out/systems/NAME)")
    return p


def run(folder: pathlib.Path, which: str, out: pathlib.Path) -> bool:
    wanted = outcome.load(folder)
    ssd_path = fmus.build(folder, out)
    system = ssd.read(ssd_path)
    names = masters.recorded(system, wanted.variables())
    holds = True
    runs = []
    for master in (masters.MASTERS if which == "both" else (which,)):
        result = masters.run(master, ssd_path, names)
        results = outcome.evaluate_all(wanted, result)
        report(result, results)
        write_csv(result, out / f"{master}.csv")
        holds &= all(r.holds for r in results)
        runs.append(result)
    if len(runs) == 2:
        diff = masters.difference(*runs)
        print(f"libcosim and fmpy {'agree' if diff == 0.0 else 'DISAGREE'}: largest difference {diff:.3g} over "
              f"{runs[0].values.size} recorded values" + (" (bitwise equal)" if diff == 0.0 else ", expected none"))
        holds &= diff == 0.0
    print(f"{system.name}: {wanted.description}: " + ("the outcome holds" if holds else "the outcome does NOT hold"))
    return holds


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    folder = args.system.resolve()
    if not (folder / "system.ssd").is_file():
        print(f"system: no system.ssd in {args.system}", file=sys.stderr)
        return 2
    out = (args.out or ROOT / "out" / "systems" / folder.name).resolve()
    try:
        return 0 if run(folder, args.master, out) else 1
    except (fmus.BuildError, masters.MasterError, ssd.SsdError, ValueError, OSError) as e:
        print(f"system: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
