"""A thin layer over fmpy's FMU2Slave for tests: a logger that records messages, value
access by variable name, and the standard call sequence."""
import ctypes
import pathlib
import shutil
import tempfile
import threading

from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                       fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE)

STATUS = {0: "OK", 1: "Warning", 2: "Discard", 3: "Error", 4: "Fatal", 5: "Pending"}
_libc = ctypes.CDLL(None)
_libc.calloc.restype = ctypes.c_void_p
_libc.calloc.argtypes = [ctypes.c_size_t, ctypes.c_size_t]
_libc.free.argtypes = [ctypes.c_void_p]

# fmpy loads an FMU's library by changing the process's working directory to the
# binaries folder and back (fmpy/fmi1.py, _FMU.__init__): two loads in threads at once
# can leave a thread in another instance's folder, which is deleted when that instance
# closes (FileNotFoundError from os.getcwd). Loads are serialised; the FMI calls are not.
_loading = threading.Lock()


class Recorder:
    """fmi2CallbackFunctions whose logger keeps (status, category, message)."""

    def __init__(self):
        self.messages = []

        def log(env, instance, status, category, message):
            self.messages.append((STATUS.get(status, status), category.decode(),
                                  message.decode().replace("%%", "%")))

        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(log)
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(_libc.calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(_libc.free)

    def text(self):
        return "\n".join(f"[{s}] {c}: {m}" for s, c, m in self.messages)

    def last(self):
        return self.messages[-1] if self.messages else None


class Slave:
    """One instance of an FMU, addressed by variable name."""

    def __init__(self, fmu, instance_name="instance", unzip_dir=None, instantiate=True):
        self.fmu = str(fmu)
        self.md = read_model_description(self.fmu)
        self.own_dir = unzip_dir is None
        self.dir = unzip_dir or extract(self.fmu, unzipdir=tempfile.mkdtemp(prefix="rigidfmu-"))
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.log = Recorder()
        with _loading:
            self.slave = FMU2Slave(guid=self.md.guid, unzipDirectory=self.dir,
                                   modelIdentifier=self.md.coSimulation.modelIdentifier,
                                   instanceName=instance_name)
        if instantiate:
            self.slave.instantiate(callbacks=self.log.callbacks, loggingOn=False)

    def real_vrs(self):
        return [v.valueReference for v in self.md.modelVariables if v.type == "Real"]

    def all_reals(self):
        return self.slave.getReal(self.real_vrs())

    def vr(self, names):
        return [self.vars[n].valueReference for n in names]

    def get(self, *names):
        values = self.slave.getReal(self.vr(names))
        return values[0] if len(names) == 1 else values

    def set_values(self, values: dict):
        reals = {n: v for n, v in values.items() if self.vars[n].type == "Real"}
        ints = {n: v for n, v in values.items() if self.vars[n].type != "Real"}
        if reals:
            self.slave.setReal(self.vr(reals), list(reals.values()))
        if ints:
            self.slave.setInteger(self.vr(ints), [int(v) for v in ints.values()])

    def initialize(self, start_values=None, start_time=0.0):
        self.slave.setupExperiment(startTime=start_time)
        if start_values:
            self.set_values(start_values)
        self.slave.enterInitializationMode()
        self.slave.exitInitializationMode()
        self.time = start_time

    def step(self, h):
        self.slave.doStep(self.time, h)
        self.time += h

    def close(self):
        try:
            self.slave.fmi2FreeInstance(self.slave.component)
        finally:
            if self.own_dir:
                shutil.rmtree(self.dir, ignore_errors=True)


def status_of(call):
    """Runs an FMI call and returns its status name ('OK', 'Discard', 'Error', ...)."""
    try:
        call()
        return "OK"
    except FMICallException as e:
        return STATUS[e.status]
