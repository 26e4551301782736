"""Parameter studies of an FMU on Dask: a grid or a random sample of parameters, start
values, input signals and scene fields; summary metrics per run; results in Parquet.

Study file (JSON, or TOML when it ends in .toml); paths are relative to it:

  {
    "scene": "../scenes/default.json",      (or "fmu": "model.fmu")
    "stopTime": 5.0, "stepSize": 0.01,      (s; communication step)
    "design": {"type": "random", "runs": 200, "seed": 1},   (or {"type": "grid"})
    "parameters":  {"ball.restitution": {"uniform": [0.1, 0.9]},   (set through FMI:
                    "floor.kineticFriction": {"values": [0.1, 0.2]}, parameters,
                    "ball.position[3]": 2.5},                        start values)
    "sceneFields": {"bodies[ball].shape.radius": {"values": [0.1, 0.12]}},
    "inputs":      {"ball.force[1]": {"values": [0, [[0, 0], [1, 5]]]}},
    "metrics": {"x_end": {"of": "slider.position[1]", "reduce": "final"},
                "speed_max": {"of": ["ball.velocity[1]", "ball.velocity[2]"], "reduce": "max"}},
    "trajectories": ["slider.position[1]"]     (optional: whole outputs in the results)
  }

A value is fixed (a number; for an input also a table [[t, v], ...], held from each
time to the next, 0 before the first), or varied: {"values": [...]} (a grid axis; drawn
uniformly among them in a random design), {"uniform"|"loguniform": [low, high]},
{"normal": [mean, sd]} (random designs). Parameters and start values go through FMI
into one FMU that each worker loads once and reuses through fmi2Reset; sceneFields
(geometry, which is no FMU parameter) give one FMU per distinct scene variant,
built once into OUT/fmus/. Reductions: initial, final, max, min, mean, time_of_max,
time_of_min, settling_time (with "threshold").

Results: OUT/results.parquet, one row per run: run, run_id, fmu, guid, the run's values
(parameter:NAME, scene:PATH, input:NAME), status (ok, discard, error, fatal, crash,
exception), reason, end_time, metric:NAME, trajectory:* if asked, worker, seconds. A
rerun skips every run with a result in OUT/parts/ (failed runs too, unless
--retry-failed).
"""
import argparse
import json
import logging
import math
import os
import pathlib
import sys
import time

import pandas as pd
from tqdm import tqdm

from rigidfmu.errors import StudyError
from rigidfmu.native import SOURCE_ROOT
from rigidfmu.study import fmus as study_fmus
from rigidfmu.study import spec as study_spec
from rigidfmu.study import store as study_store
from rigidfmu.study import worker as study_worker
from rigidfmu.study.metrics import MetricError

ROOT = SOURCE_ROOT  # the source tree: its build, scripts and docs


def parse_args(argv, prog=None):
    p = argparse.ArgumentParser(prog=prog or "rigidfmu study", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("study", type=pathlib.Path, help="the study file (.json or .toml)")
    p.add_argument("--out", type=pathlib.Path,
                   help="output directory (default out/study/<study file's name>)")
    p.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="an existing Dask scheduler (default: an embedded LocalCluster)")
    p.add_argument("--workers", type=int, default=os.cpu_count(),
                   help="worker processes of the embedded LocalCluster (default: the cores)")
    p.add_argument("--batch", type=int, help="runs per Dask task (default: about 4 tasks per worker, at most 25)")
    p.add_argument("--retry-failed", action="store_true", help="run again the runs that failed before")
    p.add_argument("--plot", nargs="?", const="", metavar="PNG",
                   help="plot each metric's distribution and its dependence on the varied values "
                        "(default OUT/<study>.png)")
    return p.parse_args(argv)


def design_frame(study, runs, fmus) -> pd.DataFrame:
    """The design columns of the results: what each run is."""
    rows = []
    for r in runs:
        row = {"run": r.index, "run_id": r.run_id, "fmu": fmus[r.variant].path.name,
               "guid": fmus[r.variant].guid}
        row.update({f"parameter:{k}": float(v) for k, v in r.parameters.items()})
        row.update({f"scene:{k}": v for k, v in r.scene_fields.items()})
        row.update({f"input:{k}": v for k, v in r.inputs.items()})
        rows.append(row)
    frame = pd.DataFrame(rows)
    for column in frame.columns:
        if column.startswith("input:") and not all(isinstance(v, (int, float)) for v in frame[column]):
            frame[column] = [json.dumps(v) for v in frame[column]]  # tables as JSON text
    return frame


def batches(todo, size):
    by_variant = {}
    for run in todo:
        by_variant.setdefault(run.variant, []).append(run)
    for runs in by_variant.values():
        for i in range(0, len(runs), size):
            yield runs[i:i + size]


def failed_rows(batch, status, reason, metrics):
    """Rows for runs that never reported (their worker died, or the batch raised)."""
    return [dict({"run_id": r.run_id, "status": status, "reason": reason, "end_time": float("nan"),
                  "worker": "", "seconds": float("nan")},
                 **{f"metric:{m}": float("nan") for m in metrics}) for r in batch]


def _has_worker_code() -> bool:
    import importlib.util
    return importlib.util.find_spec("rigidfmu.study.worker") is not None


def send_package(client):
    """The workers of an existing cluster may not have this package: its Python code
    goes to them as a zip (Dask puts it on their path) when one lacks it."""
    if all(client.run(_has_worker_code).values()):
        return
    import tempfile
    import zipfile
    package = pathlib.Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        archive = pathlib.Path(tmp) / "rigidfmu.zip"
        with zipfile.ZipFile(archive, "w") as z:
            for f in sorted(package.rglob("*.py")):
                if "node_modules" not in f.parts:
                    z.write(f, f.relative_to(package.parent))
        client.upload_file(str(archive))


def connect(args):
    """A Dask client: to the given scheduler, or to an embedded LocalCluster."""
    import dask
    from distributed import Client, LocalCluster
    if args.scheduler:
        client = Client(args.scheduler)
        send_package(client)
        return client, None
    # a run that kills its worker is retried once before it counts as a crash
    with dask.config.set({"distributed.scheduler.allowed-failures": 1}):
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR)
    return Client(cluster), cluster


def execute(client, todo, fmus, study, out, size):
    """Runs the batches on Dask; writes a part-file as each batch finishes. Returns
    the number of runs executed."""
    from distributed import as_completed
    from distributed.scheduler import KilledWorker
    experiment = {"stepSize": study.step_size, "steps": round(study.stop_time / study.step_size)}
    variables = sorted({n for spec in study.metrics.values()
                        for n in ([spec["of"]] if isinstance(spec["of"], str) else spec["of"])}
                       | set(study.trajectories))
    record = {"variables": variables, "metrics": study.metrics, "trajectories": study.trajectories}
    blobs = {key: client.scatter(fmu.path.read_bytes(), broadcast=True)
             for key, fmu in {f.key: f for f in fmus.values()}.items()}

    def submit(batch):
        fmu = fmus[batch[0].variant]
        payload = [{"run_id": r.run_id, "parameters": r.parameters, "inputs": r.inputs} for r in batch]
        return client.submit(study_worker.run_batch, fmu.key, blobs[fmu.key], payload, experiment,
                             record, pure=False)

    pending = {}
    for batch in batches(todo, size):
        pending[submit(batch)] = batch
    done = as_completed(list(pending))
    with tqdm(total=len(todo), unit="run", desc="study", file=sys.stderr, mininterval=0.5) as bar:
        for future in done:
            batch = pending.pop(future)
            if future.status == "finished":
                rows = future.result()
            else:
                error = future.exception()
                if isinstance(error, KilledWorker) and len(batch) > 1:
                    for run in batch:  # find the run that kills its worker: one task each
                        single = submit([run])
                        pending[single] = [run]
                        done.add(single)
                    continue
                status = "crash" if isinstance(error, KilledWorker) else "exception"
                rows = failed_rows(batch, status, f"{type(error).__name__}: {error}", study.metrics)
            study_store.write_part(out, rows)
            bar.update(len(rows))
    return len(todo)


def main(argv=None, prog=None):
    args = parse_args(argv, prog)
    try:
        study = study_spec.load(args.study)
    except (study_spec.StudyError, MetricError, OSError) as e:
        raise StudyError(f"study: {args.study}: {e}") from e
    out = (args.out or ROOT / "out" / "study" / study.name).resolve()
    out.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    try:
        runs = study_spec.design_runs(study)
        for r in runs:
            r.variant = study_spec.variant_key(r.scene_fields)
        fmus = study_fmus.prepare(study, sorted({r.variant for r in runs}), out)
        study_fmus.check_names(study, fmus)
    except (study_spec.StudyError, MetricError) as e:
        raise StudyError(f"study: {args.study}: {e}") from e
    for r in runs:
        r.run_id = study_spec.run_identity(r, fmus[r.variant].guid, study)
    if len({r.run_id for r in runs}) != len(runs):
        print("study: note: some runs of the design are identical; each is run once", file=sys.stderr)
    before = study_store.finished(out)
    skip = {i for i, s in before.items() if s == "ok" or not args.retry_failed}
    todo = list({r.run_id: r for r in runs if r.run_id not in skip}.values())
    workers = 0
    if todo:
        client, cluster = connect(args)
        try:
            workers = len(client.scheduler_info()["workers"])
            size = args.batch or max(1, min(25, math.ceil(len(todo) / (4 * max(workers, 1)))))
            execute(client, todo, fmus, study, out, size)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    frame = study_store.consolidate(out, design_frame(study, runs, fmus).drop_duplicates("run_id"))
    counts = frame["status"].value_counts().to_dict()
    print(f"study: {study.name}: {len(frame)} runs; executed {len(todo)}, already done "
          f"{len(frame) - len(todo)}; " + ", ".join(f"{s} {n}" for s, n in sorted(counts.items()))
          + f"; {time.perf_counter() - started:.1f} s" + (f" on {workers} workers" if todo else ""))
    print(f"study: results in {out / 'results.parquet'}")
    for _, row in frame[frame["status"] != "ok"].head(5).iterrows():
        print(f"study: run {row['run']} {row['status']}: {row['reason']}", file=sys.stderr)
    if args.plot is not None:
        from rigidfmu.study import plot as study_plot
        png = pathlib.Path(args.plot) if args.plot else out / f"{study.name}.png"
        study_plot.plot(frame, study, png)
        print(f"study: plot in {png}")


if __name__ == "__main__":
    sys.exit(main())
