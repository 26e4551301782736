"""What a Dask worker does: runs batches of a study's runs through fmpy.

Each worker thread loads an FMU once (kept by the FMU's content hash) and reuses the
instance for every further run through fmi2Reset, which gives bitwise the outputs of a
fresh instance. A run that the FMU refuses (fmi2Discard, fmi2Error, fmi2Fatal) is a
result with its status and the FMU's own message, never an exception of the batch.
"""
import pathlib
import shutil
import socket
import tempfile
import threading
import time

import numpy as np
from fmpy.fmi1 import FMICallException

from rigidfmu.driver import Fmu, Slave, Trace, status_name
from rigidfmu.study import metrics as study_metrics

_local = threading.local()  # per worker thread: FMU content hash -> LoadedFmu


class LoadedFmu:
    """One FMU unpacked and instantiated (rigidfmu.driver), with a logger that keeps
    its messages."""

    def __init__(self, fmu_bytes: bytes):
        self.dir = pathlib.Path(tempfile.mkdtemp(prefix="rigidfmu-study-", dir=_scratch()))
        path = self.dir / "model.fmu"
        path.write_bytes(fmu_bytes)
        self.model = Fmu(path, folder=self.dir)
        self.vars = self.model.vars
        self.instance = None
        self.used = False
        self._instantiate()

    def _instantiate(self):
        if self.instance is not None:
            self.instance.free()
        self.instance = Slave(self.model, "study")
        self.slave = self.instance.slave
        self.used = False

    @property
    def messages(self):
        """The FMU's messages since the run began, '[status] message'."""
        return [f"[{status.lower()}] {message}" for status, _, message in self.instance.log.messages]

    def ready(self):
        """The instance as just instantiated: reset when it has run before."""
        if self.used:
            try:
                self.slave.reset()
            except FMICallException:
                self._instantiate()  # a reset refused: start from a fresh instance
        self.used = True
        self.instance.log.clear()

    def set_values(self, values: dict):
        """One value a call, in the order given: a refused value names itself."""
        for name, value in values.items():
            self.instance.set_values({name: value})


def _scratch():
    """The Dask worker's own directory (removed with the worker), else the temp dir."""
    try:
        from distributed import get_worker
        return get_worker().local_directory
    except (ImportError, ValueError):
        return None


def _loaded(fmu_key: str, fmu_bytes: bytes) -> LoadedFmu:
    cache = getattr(_local, "fmus", None)
    if cache is None:
        cache = _local.fmus = {}
    if fmu_key not in cache:
        cache[fmu_key] = LoadedFmu(fmu_bytes)
    return cache[fmu_key]


def input_value(signal, t: float) -> float:
    """A number, or a table [[t, v], ...] held from each row's time to the next row's;
    0 before the first row."""
    if not isinstance(signal, list):
        return float(signal)
    value = 0.0
    for row_time, row_value in signal:
        if row_time <= t:
            value = float(row_value)
        else:
            break
    return value


def run_one(fmu: LoadedFmu, run: dict, experiment: dict, record: dict) -> dict:
    """One run: parameters and start values before initialisation, inputs held over
    each communication step, the recorded outputs at every communication point."""
    started = time.perf_counter()
    h, steps = experiment["stepSize"], experiment["steps"]
    trace = Trace(record["variables"])
    times = np.arange(steps + 1) * h  # t_k = k h, never accumulated

    fmu.ready()
    status, reason, reached = "ok", "", 0
    try:
        fmu.slave.setupExperiment(startTime=0.0)
        fmu.set_values(run["parameters"])
        fmu.slave.enterInitializationMode()
        fmu.slave.exitInitializationMode()
        trace.sample(fmu.instance, times[0])
        for k in range(steps):
            if run["inputs"]:
                fmu.set_values({n: input_value(s, times[k]) for n, s in run["inputs"].items()})
            fmu.slave.doStep(times[k], h)
            trace.sample(fmu.instance, times[k + 1])
            reached = k + 1
    except FMICallException as e:
        status = status_name(e.status).lower()
        said = "; ".join(m for m in fmu.messages if not m.startswith("[ok]"))
        reason = f"{e.function} returned {status} at t = {float(times[reached])!r}: {said or 'no message'}"
    except Exception as e:  # noqa: BLE001 -- a bug of this runner is the run's result too
        status, reason = "exception", f"{type(e).__name__}: {e}"
        fmu._instantiate()
    trace.finish()
    series = {n: trace.col(n) for n in trace.names}
    row = {"run_id": run["run_id"], "status": status, "reason": reason,
           "end_time": float(times[reached]), "worker": _worker_name(),
           "seconds": time.perf_counter() - started}
    for name, spec in record["metrics"].items():
        row[f"metric:{name}"] = (study_metrics.reduce(spec, times, series)
                                 if status == "ok" else float("nan"))
    if record["trajectories"]:
        row["trajectory:time"] = times[:reached + 1]
        for n in record["trajectories"]:
            row[f"trajectory:{n}"] = series[n][:reached + 1]
    return row


def _worker_name() -> str:
    try:
        from distributed import get_worker
        return get_worker().address
    except (ImportError, ValueError):  # run outside a Dask worker
        return socket.gethostname()


def run_batch(fmu_key: str, fmu_bytes: bytes, runs: list, experiment: dict, record: dict) -> list:
    """The task Dask runs: a batch of runs of one FMU, one row per run."""
    fmu = _loaded(fmu_key, fmu_bytes)
    return [run_one(fmu, run, experiment, record) for run in runs]


def unload_all():
    """Frees this thread's instances and their unpacked files."""
    for fmu in getattr(_local, "fmus", {}).values():
        try:
            fmu.instance.free()
        finally:
            shutil.rmtree(fmu.dir, ignore_errors=True)
    _local.fmus = {}
