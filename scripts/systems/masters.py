"""One system.ssd run in two masters, recording the same variables at the same
communication points:

- **libcosim** (PyPI libcosimpy, the Open Simulation Platform's engine): it reads the
  SSD itself and runs its fixed-step algorithm;
- **fmpy**: the same SSD read by `ssd.py` and the FMUs stepped here in libcosim's
  order, so that both pass the same values at the same points. Per communication
  point, as libcosim's fixed-step algorithm does: every FMU sets the inputs transferred
  to it, steps from t_k = k h (h a whole number of nanoseconds, t_k converted as
  libcosim converts it) by t_{k+1} - t_k, and gives its outputs; then the outputs are
  transferred to the inputs they are connected to (Jacobi). Initialisation: parameters
  in the instantiated state, fmi2SetupExperiment and fmi2EnterInitializationMode, as
  many rounds of set, get and transfer as there are FMUs, then
  fmi2ExitInitializationMode, get and transfer.

A run is the outputs named `component.variable` after each step (steps 1..n)."""
import pathlib
import time
from dataclasses import dataclass

import numpy as np

from systems import ssd

MASTERS = ("libcosim", "fmpy")


class MasterError(RuntimeError):
    pass


@dataclass
class Run:
    master: str
    system: ssd.System
    names: list[str]  # component.variable
    t: np.ndarray  # s, the communication points after each step
    values: np.ndarray  # a row a point, a column a name
    seconds: float  # wall time of the run, loading the FMUs included

    def col(self, name: str) -> np.ndarray:
        return self.values[:, self.names.index(name)]


def split(name: str) -> tuple[str, str]:
    component, _, variable = name.partition(".")
    return component, variable


def seconds_at(system: ssd.System, k: int) -> float:
    """Communication point k as libcosim passes it: a whole number of ns to double."""
    return (round(system.start * ssd.NANOSECONDS) + k * system.step_ns) / ssd.NANOSECONDS


def recorded(system: ssd.System, wanted) -> list[str]:
    """The variables a run records: the `wanted` ones and every connected output."""
    return sorted(set(wanted) | {f"{c.source}.{c.output}" for c in system.connections})


def difference(a: Run, b: Run) -> float:
    """The largest |a - b| over every recorded variable and point (inf if the points
    differ). libcosim and fmpy pass the same values at the same communication points,
    so it is 0: only whose code runs the loop differs."""
    if a.names != b.names or not np.array_equal(a.t, b.t):
        return float("inf")
    return float(np.max(np.abs(a.values - b.values)))


def run(master: str, ssd_path, names) -> Run:
    if master not in MASTERS:
        raise MasterError(f"unknown master {master}: one of {', '.join(MASTERS)}")
    return (run_libcosim if master == "libcosim" else run_fmpy)(pathlib.Path(ssd_path), list(names))


# ---- libcosim ---------------------------------------------------------------------------


def _references(execution, names):
    """{name: (slave index, value reference)} of Real variables."""
    from libcosimpy.CosimEnums import CosimVariableType

    out = {}
    for component in {split(n)[0] for n in names}:
        index = execution.slave_index_from_instance_name(component)
        if index is None:
            raise MasterError(f"libcosim: no component {component} in the system")
        variables = {v.name.decode(): v for v in execution.slave_variables(index)}
        for name in (n for n in names if split(n)[0] == component):
            variable = variables.get(split(name)[1])
            if variable is None or variable.type != CosimVariableType.REAL.value:
                raise MasterError(f"libcosim: {name} is not a Real variable of {component}")
            out[name] = (index, variable.reference)
    return out


def run_libcosim(ssd_path: pathlib.Path, names: list[str]) -> Run:
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    system = ssd.read(ssd_path)
    # Its FMI Library calls rigidfmu's independent variable `time` an error for lacking
    # the start value that FMI 2.0 forbids it; the names were checked (fmus.py) and a
    # failed run reports libcosim's last error.
    log_output_level(CosimLogLevel.FATAL)
    began = time.perf_counter()
    execution = CosimExecution.from_ssp_file(str(ssd_path), step_size=system.step_ns)
    observer = CosimObserver.create_time_series(buffer_size=system.steps + 1)
    execution.add_observer(observer)
    references = _references(execution, names)
    for index, reference in references.values():
        observer.start_time_series(index, reference, CosimVariableType.REAL)
    stop_ns = round(system.stop * ssd.NANOSECONDS)
    if not execution.simulate_until(stop_ns):
        from libcosimpy._internal import get_last_error_message

        raise MasterError(f"libcosim: the run stopped: {get_last_error_message()}")
    seconds = time.perf_counter() - began
    columns, times = [], None
    for name in names:
        # from step 1: the wrapper counts step number 0 as an empty slot
        t_ns, steps, values = observer.time_series_real_samples(*references[name], from_step=1,
                                                               sample_count=system.steps)
        if list(steps) != list(range(1, system.steps + 1)):
            raise MasterError(f"libcosim: {name}: samples of steps {steps[:1]}..{steps[-1:]}, "
                              f"expected 1..{system.steps}")
        times = np.array(t_ns) / ssd.NANOSECONDS
        columns.append(values)
    return Run("libcosim", system, names, times, np.array(columns).T, seconds)


# ---- fmpy ---------------------------------------------------------------------------------


class _Component:
    """One FMU instance (rigidfmu's driver over fmpy) with the inputs waiting for it."""

    def __init__(self, name, fmu):
        from rigidfmu.driver import Slave

        self.name = name
        self.slave = Slave(fmu, instance_name=name, instantiate=False)
        self.slave.instantiate()
        self.fmi = self.slave.slave
        self.pending = {}  # value reference -> value, set before the next call

    def vr(self, variable):
        if variable not in self.slave.vars:
            raise MasterError(f"fmpy: {self.name} has no variable {variable}")
        return self.slave.vars[variable].valueReference

    def set_pending(self):
        if self.pending:
            self.fmi.setReal(list(self.pending), list(self.pending.values()))
            self.pending = {}


def _exchange(components, connections, outputs):
    """Every FMU's outputs read (`outputs`: component -> [(variable, vr)]), then each
    connection's value given to its target for its next call."""
    read = {}
    for name, wanted in outputs.items():
        values = components[name].fmi.getReal([vr for _, vr in wanted]) if wanted else []
        read.update({(name, variable): value for (variable, _), value in zip(wanted, values)})
    for c in connections:
        target = components[c.target]
        target.pending[target.vr(c.input)] = read[(c.source, c.output)]
    return read


def _initialise(system, components, connections, outputs):
    for name, component in components.items():
        if system.parameters.get(name):
            component.slave.set_values(system.parameters[name])
        component.fmi.setupExperiment(startTime=system.start)
        component.fmi.enterInitializationMode()
    for _ in range(len(components)):
        for component in components.values():
            component.set_pending()
        _exchange(components, connections, outputs)
    for component in components.values():
        component.set_pending()
        component.fmi.exitInitializationMode()
    _exchange(components, connections, outputs)


def run_fmpy(ssd_path: pathlib.Path, names: list[str]) -> Run:
    system = ssd.read(ssd_path)
    began = time.perf_counter()
    components = {name: _Component(name, ssd_path.parent / source) for name, source in system.components.items()}
    try:
        wanted = {(c.source, c.output) for c in system.connections} | {split(n) for n in names}
        outputs = {name: [(v, components[name].vr(v)) for (c, v) in sorted(wanted) if c == name]
                   for name in components}
        _initialise(system, components, system.connections, outputs)
        rows = []
        for k in range(system.steps):
            t, t_next = seconds_at(system, k), seconds_at(system, k + 1)
            for component in components.values():
                component.set_pending()
                component.fmi.doStep(t, t_next - t)
            read = _exchange(components, system.connections, outputs)
            rows.append([read[split(n)] for n in names])
        for component in components.values():
            component.fmi.terminate()
    except Exception as e:
        messages = "; ".join(f"{c.name}: {c.slave.log.text()}" for c in components.values() if c.slave.log.messages)
        raise MasterError(f"fmpy: the run stopped: {e}" + (f" ({messages})" if messages else "")) from e
    finally:
        for component in components.values():
            component.slave.close()
    seconds = time.perf_counter() - began
    times = np.array([seconds_at(system, k + 1) for k in range(system.steps)])
    return Run("fmpy", system, names, times, np.array(rows), seconds)
