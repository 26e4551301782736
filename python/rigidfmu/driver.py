"""The one FMU driver over fmpy's FMU2Slave, used by the tests, the reports, the studies
and the benchmarks alike: an FMU unpacked once (`Fmu`), instances addressed by variable
name (`Slave`: set values, initialise, step, get outputs, close), an FMI logger that
records the FMU's messages (`Recorder`), a trace of outputs over the communication
points (`Trace`) and the status of a call (`status_of`).

fmpy loads an FMU's library by changing the process's working directory to the binaries
folder and back (fmpy/fmi1.py, _FMU.__init__): two loads in threads at once can leave a
thread in another instance's folder, which is deleted when that instance closes
(FileNotFoundError from os.getcwd). Every load goes through `load_library`, which
serialises the loads (and only the loads: the FMI calls run in parallel)."""
import ctypes
import shutil
import tempfile
import threading

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)

STATUS = {0: "OK", 1: "Warning", 2: "Discard", 3: "Error", 4: "Fatal", 5: "Pending"}
FAILED = ("Discard", "Error", "Fatal")

_libc = ctypes.CDLL(None)
_libc.calloc.restype = ctypes.c_void_p
_libc.calloc.argtypes = [ctypes.c_size_t, ctypes.c_size_t]
_libc.free.argtypes = [ctypes.c_void_p]
_loading = threading.Lock()


def status_name(status) -> str:
    return STATUS.get(status, str(status))


class Recorder:
    """fmi2CallbackFunctions whose logger keeps (status, category, message): the first
    `cap` messages (all when cap is None) and a count per status. The FMU's messages are
    printf formats, their '%' come doubled; a message that is not UTF-8 (a corrupt
    state's bytes quoted in it) is kept with replacement characters, and also in
    `not_utf8`. A subclass sees every message through `note`."""

    def __init__(self, cap=None):
        self.cap = cap
        self.messages = []
        self.counts = {}
        self.not_utf8 = []

        def log(env, instance, status, category, message):
            try:
                text = message.decode() if message else ""
            except UnicodeDecodeError:
                text = message.decode(errors="replace")
                self.not_utf8.append(text)
            self.note(status_name(status), category.decode(errors="replace") if category else "",
                      text.replace("%%", "%"))

        self.callbacks = fmi2CallbackFunctions()  # kept: the FMU calls into it
        self.callbacks.logger = fmi2CallbackLoggerTYPE(log)
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(_libc.calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(_libc.free)

    def note(self, status, category, message):
        self.counts[status] = self.counts.get(status, 0) + 1
        if self.cap is None or len(self.messages) < self.cap:
            self.messages.append((status, category, message))

    def text(self):
        return "\n".join(f"[{s}] {c}: {m}" for s, c, m in self.messages)

    def last(self):
        return self.messages[-1] if self.messages else None

    def clear(self):
        self.messages.clear()
        self.counts.clear()


def load_library(md, unzip_dir, instance_name):
    """fmpy's FMU2Slave, or FMU3Slave for an FMI 3.0 FMU, of an unpacked FMU (its
    library loaded, not instantiated)."""
    slave = FMU2Slave
    if md.fmiVersion.startswith("3"):
        from fmpy.fmi3 import FMU3Slave as slave
    with _loading:
        return slave(guid=md.guid, unzipDirectory=unzip_dir, modelIdentifier=md.coSimulation.modelIdentifier,
                     instanceName=instance_name)


class Fmu:
    """One FMU file: its model description, its variables by name and one unpacked copy
    (`unzip_dir`, or a new folder `prefix`* in `folder`, removed by close())."""

    def __init__(self, fmu, unzip_dir=None, folder=None, prefix="rigidfmu-"):
        self.path = str(fmu)
        self.md = read_model_description(self.path)
        self.own_dir = unzip_dir is None
        self.dir = unzip_dir or extract(self.path, unzipdir=tempfile.mkdtemp(prefix=prefix, dir=folder))
        self.vars = {v.name: v for v in self.md.modelVariables}

    def methods(self):
        """[(name, value, description)] of the Enumeration SolverMethod ([] without it)."""
        for t in self.md.typeDefinitions:
            if t.name == "SolverMethod":
                return [(i.name, int(i.value), i.description or "") for i in t.items]
        return []

    def real_outputs(self):
        return [v for v in self.md.modelVariables if v.causality == "output" and v.type == "Real"]

    def log_categories(self):
        return [c if isinstance(c, str) else getattr(c, "name", str(c))
                for c in (self.md.logCategories or [])]

    def instance(self, instance_name="instance", **options) -> "Slave":
        return Slave(self, instance_name, **options)

    def close(self):
        if self.own_dir:
            shutil.rmtree(self.dir, ignore_errors=True)


class Slave:
    """One instance of an FMU (a path, or an `Fmu` shared by several instances),
    addressed by variable name. Its messages go to `log`, a `Recorder` (or the given
    one); `recorder=False` leaves them to fmpy's default logger, which prints them.
    `slave` is fmpy's FMU2Slave, for the calls this class does not wrap."""

    def __init__(self, fmu, instance_name="instance", unzip_dir=None, instantiate=True,
                 recorder=None, logging_on=False, folder=None, prefix="rigidfmu-"):
        self.model = fmu if isinstance(fmu, Fmu) else Fmu(fmu, unzip_dir, folder, prefix)
        self.own_model = not isinstance(fmu, Fmu)
        self.fmu, self.md, self.dir = self.model.path, self.model.md, self.model.dir
        self.vars = self.model.vars
        self.log = None if recorder is False else (recorder or Recorder())
        self.slave = load_library(self.md, self.dir, instance_name)
        self.time = 0.0
        if instantiate:
            self.instantiate(logging_on)

    def instantiate(self, logging_on=False):
        self.slave.instantiate(callbacks=self.log.callbacks if self.log else None,
                               loggingOn=logging_on)

    def real_vrs(self):
        return [v.valueReference for v in self.md.modelVariables if v.type == "Real"]

    def all_reals(self):
        return self.slave.getReal(self.real_vrs())

    def vr(self, names):
        return [self.vars[n].valueReference for n in names]

    def get(self, *names):
        """The Reals named: one value for one name, else a list."""
        values = self.slave.getReal(self.vr(names))
        return values[0] if len(names) == 1 else values

    def get_values(self, names):
        """{name: value} of Reals and Integers (Enumerations) alike."""
        reals = [n for n in names if self.vars[n].type == "Real"]
        ints = [n for n in names if self.vars[n].type != "Real"]
        out = dict(zip(reals, self.slave.getReal(self.vr(reals)) if reals else []))
        out.update(zip(ints, self.slave.getInteger(self.vr(ints)) if ints else []))
        return out

    def set_values(self, values: dict):
        """Sets Reals in one fmi2SetReal and Integers (Enumerations) in one fmi2SetInteger."""
        reals = {n: v for n, v in values.items() if self.vars[n].type == "Real"}
        ints = {n: v for n, v in values.items() if self.vars[n].type != "Real"}
        if reals:
            self.slave.setReal(self.vr(reals), [float(v) for v in reals.values()])
        if ints:
            self.slave.setInteger(self.vr(ints), [int(v) for v in ints.values()])

    def initialize(self, start_values=None, start_time=0.0):
        """fmi2SetupExperiment, the start values, fmi2Enter/ExitInitializationMode."""
        self.slave.setupExperiment(startTime=start_time)
        if start_values:
            self.set_values(start_values)
        self.slave.enterInitializationMode()
        self.slave.exitInitializationMode()
        self.time = start_time

    def step(self, h, t=None):
        """fmi2DoStep(t, h) from `t` (default: where the last step ended)."""
        t = self.time if t is None else t
        self.slave.doStep(t, h)
        self.time = t + h

    def free(self):
        """fmi2FreeInstance and the library (the unpacked files stay)."""
        self.slave.freeInstance()

    def close(self):
        """fmi2FreeInstance; the unpacked files go when this instance unpacked them."""
        try:
            self.slave.fmi2FreeInstance(self.slave.component)
        finally:
            if self.own_model:
                self.model.close()


class Trace:
    """Outputs by name at communication points: `sample` reads them (Reals and
    Integers) after initialisation and after each step; `finish` makes the arrays
    `t` and `data` (a row a point), `col` and `vec` read them."""

    def __init__(self, names):
        self.names = list(names)
        self.index = {n: i for i, n in enumerate(self.names)}
        self.times, self.rows = [], []

    def sample(self, slave: Slave, t):
        values = slave.get_values(self.names)
        row = np.array([values[n] for n in self.names], dtype=float)
        self.times.append(t)
        self.rows.append(row)
        return row

    def finish(self):
        self.t = np.array(self.times)
        self.data = np.array(self.rows) if self.rows else np.zeros((0, len(self.names)))
        return self

    def col(self, name):
        return self.data[:, self.index[name]]

    def vec(self, prefix, n=3):
        return np.column_stack([self.col(f"{prefix}[{i}]") for i in range(1, n + 1)])


def status_of(call):
    """Runs an FMI call and returns its status name ('OK', 'Discard', 'Error', ...)."""
    try:
        call()
        return "OK"
    except FMICallException as e:
        return STATUS[e.status]
