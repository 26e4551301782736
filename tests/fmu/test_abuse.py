"""Abuse: the FMU driven the way no sane master drives it.

1. Fuzzing: random sequences of FMI calls with hostile arguments (NaN, ±Inf, ±1e308,
   0, negative numbers, unknown value references, random and truncated state bytes,
   stale and foreign FMU-state pointers, unknown log categories, NULL pointers), on
   every example scene and on the Playground with conveyors, each scene in its own
   process so that a crash is a failing exit code reported with the seed and the last
   calls.
2. Eight instances in eight threads give the serial results bitwise.
3. The same inputs give bitwise the same outputs in two processes.
4. valgrind: instantiate/step/state/free cycles leak nothing and touch no invalid memory.
"""
import ctypes
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import traceback

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Boolean, fmi2Byte, fmi2FMUstate, fmi2Integer, fmi2Real, fmi2String, fmi2ValueReference

from rigidfmu.driver import STATUS, Recorder, Slave, load_library

TESTS = pathlib.Path(__file__).resolve().parent
ROOT = TESTS.parents[1]
SCENE_DIR = ROOT / "scripts" / "scenes"
EXAMPLES = ["default.json", "spinner.json", "tumble.json", "thruster.json", "pusher.json", "crane.json"]
# Set by scripts/sanitize.sh: the FMUs are the ASan/UBSan build and the runtimes are
# preloaded (LD_PRELOAD) into this process and its children.
SANITIZED = os.environ.get("RIGIDFMU_SANITIZED") == "1"


def example(name):
    return json.loads((SCENE_DIR / name).read_text())


PLAYGROUND = example("default.json")


def with_belts(scene):
    """The scene with its surfaces made conveyors (inputs S.beltVelocity[1..3]): belts
    along x in the world frame, so that on a tilted surface part of it is normal (and
    ignored)."""
    belted = [dict(s, beltVelocity=[0.3 * (k + 1), 0.0, 0.0]) for k, s in enumerate(scene["surfaces"])]
    return dict(scene, name=scene["name"] + "Belts", surfaces=belted)


FUZZ_SCENES = {"default-belts.json": with_belts(PLAYGROUND)}  # beside the example scenes


# =====================================================================================
# Shared helpers (also used by the child processes, which import this module)
# =====================================================================================

def real_vrs(md):
    return [v.valueReference for v in md.modelVariables if v.type == "Real"]


def int_vrs(md):
    return [v.valueReference for v in md.modelVariables if v.type in ("Integer", "Enumeration")]


def real_inputs(md):
    return [v for v in md.modelVariables if v.type == "Real" and v.causality == "input"]


def outputs(slave, md):
    """Every Real and Integer value of the instance, as bytes (bitwise comparison)."""
    reals = slave.getReal(real_vrs(md))
    ints = slave.getInteger(int_vrs(md)) if int_vrs(md) else []
    return np.array(reals, dtype=np.float64).tobytes() + np.array(ints, dtype=np.int64).tobytes()


def input_signal(md, k, phase=0.0, amplitude=1.0):
    """A scripted input signal: every Real input gets a different sine of step k; a
    driven body's orientation a unit quaternion turning about z by such a sine."""
    vrs, values = [], []
    for j, v in enumerate(real_inputs(md)):
        a = 5.0 if ".force[" in v.name else 0.5
        vrs.append(v.valueReference)
        if ".orientation[" in v.name:
            half = 0.5 * amplitude * math.sin(0.37 * k + phase)
            values.append([math.cos(half), 0.0, 0.0, math.sin(half)][int(v.name[-2]) - 1])
        else:
            values.append(amplitude * a * math.sin(0.37 * k + 0.9 * j + phase))
    return vrs, values


# =====================================================================================
# 1. Fuzzing
# =====================================================================================

NUMERIC_ABUSE = [float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 0.0, -1.0, -1e-3,
                 5e-324, -5e-324, 1e-300]
LOG_CATEGORIES = [b"logEvents", b"logStatusWarning", b"logStatusDiscard", b"logStatusError",
                  b"logStatusFatal", b"logAll", b"logCalls", b"nonsense", b"", b"logevents",
                  b"%s%n%s", "\u00e9t\u00e9".encode()]
SLOW_STEP = 0.3  # s
NORMAL_STEP = 0.01
NORMAL_STEPS = 10


class Violation(Exception):
    pass


class Fuzzer:
    """Drives one instance of an FMU (plus a reference instance) with random calls."""

    def __init__(self, fmu, unzip_dir, seed, n_calls, trace):
        self.md = read_model_description(fmu)
        self.dir = unzip_dir
        self.seed = seed
        self.n_calls = n_calls
        self.rng = np.random.default_rng(seed)
        self.trace = trace
        self.recent = []  # the last calls, for the report
        self.violations = []
        self.counts = {}
        self.seconds = {}
        self.slowest = (0.0, "")
        self.slow = []  # communication steps slower than SLOW_STEP
        self.reals = real_vrs(self.md)
        self.ints = int_vrs(self.md)
        self.vars = {v.valueReference: v for v in self.md.modelVariables}
        self.time_vr = next(v.valueReference for v in self.md.modelVariables if v.name == "time")
        self.n_vars = len(self.md.modelVariables)
        self.blobs = []       # serialisations seen, for deserialisation
        self.foreign = []     # live states of the reference instance
        self.slave = self.reference = None

    # ---- instances -------------------------------------------------------------------

    def new_slave(self, name):
        # the driver's Recorder keeps a message that is not UTF-8 (a corrupt state's bytes
        # quoted in it) with replacement characters, instead of losing it to a
        # UnicodeDecodeError inside the ctypes callback
        log = Recorder()
        s = load_library(self.md, self.dir, name)
        s.instantiate(callbacks=log.callbacks, loggingOn=False)
        s.rec = log
        return s

    def instantiate_fuzzed(self):
        self.slave = self.new_slave(f"fuzz{self.seed}")
        self.log = self.slave.rec
        self.states = []   # live states of the fuzzed instance (pointer values)
        self.freed = []    # pointers given back by fmi2FreeFMUstate
        self.time = 0.0
        # the state right after initialisation, for the restore check
        self.checked("normal setup", self.normal_initialise, self.slave)
        st = fmi2FMUstate()
        self.call("fmi2GetFMUstate", self.c, ctypes.byref(st))
        self.s0 = st.value
        self.time = 0.0

    @property
    def c(self):
        return self.slave.component

    def normal_initialise(self, s):
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.exitInitializationMode()

    def normal_steps(self, s):
        """NORMAL_STEPS steps with a scripted input signal; the outputs after each."""
        out = [outputs(s, self.md)]
        for k in range(NORMAL_STEPS):
            vrs, values = input_signal(self.md, k)
            if vrs:
                s.setReal(vrs, values)
            s.doStep(k * NORMAL_STEP, NORMAL_STEP)
            out.append(outputs(s, self.md))
        return out

    # ---- recording and checking ------------------------------------------------------

    def note(self, text):
        self.recent.append(text)
        del self.recent[:-25]
        self.trace.write(f"seed {self.seed}: {text}")
        self.trace.flush()

    def violation(self, what):
        self.violations.append({"seed": self.seed, "what": what, "last calls": list(self.recent)})
        if len(self.violations) >= 5:
            raise Violation(what)

    def call(self, name, *args, describe=None, log_required=True, slave=None):
        """Calls slave.<name>(*args) (a low-level fmi2 function) and checks its status."""
        slave = slave or self.slave
        self.note(f"{name}({describe if describe is not None else self.args_text(args)})")
        before = len(slave.rec.messages)
        t0 = time.perf_counter()
        try:
            status = getattr(slave, name)(*args)
        except FMICallException as e:
            status = e.status
        dt = time.perf_counter() - t0
        self.seconds[name] = self.seconds.get(name, 0.0) + dt
        if dt > self.slowest[0]:
            self.slowest = (dt, self.recent[-1])
        self.trace.write(f" -> {STATUS.get(status, status)}\n")
        self.trace.flush()
        self.recent[-1] += f" -> {STATUS.get(status, status)}"
        key = f"{name} {STATUS.get(status, status)}"
        self.counts[key] = self.counts.get(key, 0) + 1
        if status not in (0, 1, 2, 3):
            self.violation(f"{name} returned {STATUS.get(status, 'illegal code')} ({status})")
        elif status != 0 and log_required:
            new = slave.rec.messages[before:]
            if not any(m[0] == STATUS[status] for m in new):
                self.violation(f"{name} returned {STATUS[status]} without a {STATUS[status]} "
                               f"message through the logger (messages: {new})")
        return status

    def checked(self, what, run, *args):
        """Runs a normal sequence (fmpy's wrappers): every status must be OK."""
        self.note(what)
        try:
            result = run(*args)
        except FMICallException as e:
            self.trace.write(" -> failed\n")
            self.violation(f"{what}: {e} ({args[0].rec.text()[-500:] if args else ''})")
            return None
        self.trace.write(" -> OK\n")
        self.recent[-1] += " -> OK"
        return result

    @staticmethod
    def args_text(args):
        out = []
        for a in args[1:]:
            if isinstance(a, ctypes.Array):
                out.append(repr(list(a)[:8]) if len(a) < 64 else f"<{len(a)} items>")
            elif isinstance(a, ctypes._SimpleCData):
                out.append(repr(a.value))
            else:
                out.append(repr(a))
        return ", ".join(out)

    # ---- random arguments ----------------------------------------------------------------

    def pick(self, seq):
        return seq[int(self.rng.integers(len(seq)))]

    def number(self, typical=1.0):
        r = self.rng.random()
        if r < 0.45:
            return self.pick(NUMERIC_ABUSE)
        if r < 0.75:
            return float(typical * self.rng.uniform(0.5, 1.5))
        return float(self.rng.uniform(-100.0, 100.0))

    def value_refs(self, valid, n):
        out = []
        for _ in range(n):
            r = self.rng.random()
            if r < 0.75 and valid:
                out.append(int(self.pick(valid)))
            elif r < 0.85:
                out.append(int(self.rng.integers(0, self.n_vars)))  # maybe of the other type
            else:
                out.append(int(self.pick([self.n_vars, self.n_vars + 7, 2**31, 2**32 - 1,
                                          int(self.rng.integers(self.n_vars, 2**32))])))
        return out

    def start_of(self, vr):
        v = self.vars.get(vr)
        try:
            return float(v.start) if v is not None and v.start is not None else 1.0
        except ValueError:
            return 1.0

    def right_time(self):
        value = (fmi2Real * 1)()
        vr = (fmi2ValueReference * 1)(self.time_vr)
        if self.call("fmi2GetReal", self.c, vr, 1, value) == 0:
            self.time = value[0]
        return self.time

    # ---- the operations ------------------------------------------------------------------

    def op_setup(self):
        start = self.pick([0.0, 0.0, 1.5, -2.0, 1e308, -1e308] + NUMERIC_ABUSE)
        self.call("fmi2SetupExperiment", self.c, int(self.rng.integers(0, 3)), self.number(1e-4),
                  start, int(self.rng.integers(0, 3)), self.number(10.0))

    def op_enter(self):
        self.call("fmi2EnterInitializationMode", self.c)

    def op_exit(self):
        self.call("fmi2ExitInitializationMode", self.c)

    def op_step(self):
        r = self.rng.random()
        tc = self.right_time() if r < 0.8 else self.pick(NUMERIC_ABUSE + [self.time + 1.0])
        r = self.rng.random()
        # mostly one or two internal steps: hostile (finite) inputs can make every
        # internal step sub-step 1e5 times, and the run must stay short
        h = (float(self.rng.uniform(1e-4, 2e-3)) if r < 0.55 else
             float(self.rng.uniform(2e-3, 0.03)) if r < 0.65 else self.pick(NUMERIC_ABUSE))
        t0 = time.perf_counter()
        self.call("fmi2DoStep", self.c, tc, h, int(self.rng.integers(0, 2)))
        if time.perf_counter() - t0 > SLOW_STEP:
            # sub-stepping at its cap: noted, not a failure; leave the regime by a reset
            self.slow.append(f"seed {self.seed}: {self.recent[-1]} took "
                             f"{time.perf_counter() - t0:.2f} s")
            self.op_check_reset()

    def op_get_real(self):
        n = int(self.rng.integers(0, 6))
        vrs = self.value_refs(self.reals, n)
        value = (fmi2Real * max(n, 1))()
        vr = (fmi2ValueReference * max(n, 1))(*vrs)
        if n and self.rng.random() < 0.05:
            self.call("fmi2GetReal", self.c, None, n, value)
            return
        if self.call("fmi2GetReal", self.c, vr, n, value) == 0:
            bad = [(vrs[i], value[i]) for i in range(n) if not math.isfinite(value[i])]
            if bad:
                self.violation(f"fmi2GetReal returned OK with non-finite values "
                               f"{[(self.vars[v].name, x) for v, x in bad]}")

    def op_get_integer(self):
        n = int(self.rng.integers(0, 4))
        vrs = self.value_refs(self.ints, n)
        value = (fmi2Integer * max(n, 1))()
        self.call("fmi2GetInteger", self.c, (fmi2ValueReference * max(n, 1))(*vrs), n, value)

    def op_set_real(self):
        n = int(self.rng.integers(0, 4))
        vrs = self.value_refs(self.reals, n)
        values = [self.number(self.start_of(vr) or 1.0) for vr in vrs]
        if n and self.rng.random() < 0.05:
            self.call("fmi2SetReal", self.c, (fmi2ValueReference * n)(*vrs), n, None)
            return
        self.call("fmi2SetReal", self.c, (fmi2ValueReference * max(n, 1))(*vrs), n,
                  (fmi2Real * max(n, 1))(*values))

    def op_set_integer(self):
        n = int(self.rng.integers(0, 3))
        vrs = self.value_refs(self.ints, n)
        values = [int(self.pick([-1, 0, 1, 2, 3, 4, 5, 99, 2**31 - 1, -2**31])) for _ in vrs]
        self.call("fmi2SetInteger", self.c, (fmi2ValueReference * max(n, 1))(*vrs), n,
                  (fmi2Integer * max(n, 1))(*values))

    def op_bool_string(self):
        n = int(self.rng.integers(0, 3))
        vr = (fmi2ValueReference * max(n, 1))(*self.value_refs([], n))
        kind = self.pick(["fmi2GetBoolean", "fmi2SetBoolean", "fmi2GetString", "fmi2SetString"])
        values = (fmi2Boolean if "Boolean" in kind else fmi2String) * max(n, 1)
        self.call(kind, self.c, vr, n, values())

    def op_terminate(self):
        self.call("fmi2Terminate", self.c)

    def op_reset(self):
        self.call("fmi2Reset", self.c)
        self.time = 0.0

    def op_get_state(self):
        st = fmi2FMUstate()
        r = self.rng.random()
        if r < 0.2 and self.states:
            st.value = self.pick(self.states)  # overwrite an existing state
        elif r < 0.3:
            st.value = self.pick(self.stale() + self.foreign + [12345, 0xDEADBEEF])
        if self.call("fmi2GetFMUstate", self.c, ctypes.byref(st)) == 0 and st.value not in self.states:
            self.states.append(st.value)

    def stale(self):
        """Freed pointers (an address may have been reused for a live state: never s0's)."""
        return [p for p in self.freed if p != self.s0]

    def any_state(self):
        r = self.rng.random()
        if r < 0.6 and self.states:
            return self.pick(self.states)
        if r < 0.7:
            return self.s0
        return self.pick(self.stale() + self.foreign + [None, 8, 0xDEADBEEF0])

    def op_set_state(self):
        st = self.any_state()
        if self.call("fmi2SetFMUstate", self.c, fmi2FMUstate(st)) == 0:
            self.right_time()

    def op_free_state(self):
        candidates = [s for s in self.states if s != self.s0]
        st = fmi2FMUstate(self.pick(candidates) if candidates and self.rng.random() < 0.7
                          else self.pick(self.stale() + self.foreign + [None, 4242, self.s0]))
        if st.value == self.s0:
            # freeing s0 is not abuse (it is allowed): keep it and only free a stale pointer
            st = fmi2FMUstate(self.pick(self.stale() + [None, 4242]))
        before = st.value
        if self.call("fmi2FreeFMUstate", self.c, ctypes.byref(st)) == 0 and before:
            if st.value is not None:
                self.violation(f"fmi2FreeFMUstate returned OK but left *FMUstate = {st.value:#x}")
            if before in self.states:
                self.states.remove(before)
                self.freed.append(before)

    def op_serialize(self):
        st = fmi2FMUstate(self.any_state())
        size = ctypes.c_size_t(0)
        if self.call("fmi2SerializedFMUstateSize", self.c, st, ctypes.byref(size)) != 0:
            return
        n = size.value
        if n > 1 << 24:
            self.violation(f"fmi2SerializedFMUstateSize gave {n} bytes")
            return
        short = self.rng.random() < 0.2
        buf = (fmi2Byte * max(n, 1))()
        status = self.call("fmi2SerializeFMUstate", self.c, st, buf, n - 1 if short else n)
        if short and status == 0:
            self.violation("fmi2SerializeFMUstate accepted a buffer one byte short")
        if status == 0:
            self.blobs.append(buf.raw[:n])
            del self.blobs[:-8]

    def random_bytes(self):
        r = self.rng.random()
        if self.blobs and r < 0.35:
            return self.pick(self.blobs)  # a genuine one
        if self.blobs and r < 0.55:
            b = self.pick(self.blobs)
            return b[:int(self.rng.integers(0, len(b)))]  # truncated
        if self.blobs and r < 0.65:
            return self.pick(self.blobs) + bytes(self.rng.integers(0, 256, 5, dtype=np.uint8))
        if self.blobs and r < 0.85:
            # a genuine state with the header (magic, version, GUID, counts, machine
            # state) corrupted: refused, or accepted as a consistent state
            b = bytearray(self.pick(self.blobs))
            guid_len = int.from_bytes(b[12:16], "little")
            header = 16 + guid_len + 9
            i = int(self.rng.integers(0, min(header, len(b))))
            b[i] ^= int(self.rng.integers(1, 256))
            return bytes(b)
        n = int(self.pick([0, 1, 8, 16, 100, 2000]))
        data = bytes(self.rng.integers(0, 256, n, dtype=np.uint8))
        return (b"RIGIDFMU" + data) if self.rng.random() < 0.5 else data

    def op_deserialize(self):
        data = self.random_bytes()
        st = fmi2FMUstate()
        if self.states and self.rng.random() < 0.2:
            st.value = self.pick(self.states)  # into an existing state
        elif self.rng.random() < 0.1:
            st.value = self.pick(self.stale() + self.foreign + [77])
        buf = (fmi2Byte * max(len(data), 1)).from_buffer_copy(data.ljust(1, b"\0"))
        status = self.call("fmi2DeSerializeFMUstate", self.c,
                           None if self.rng.random() < 0.03 else buf, len(data), ctypes.byref(st),
                           describe=f"<{len(data)} bytes {data[:24]!r}...>")
        if status == 0:
            if st.value not in self.states:
                self.states.append(st.value)
            if self.rng.random() < 0.7:
                if self.call("fmi2SetFMUstate", self.c, st) == 0:
                    self.right_time()

    def op_status(self):
        name = self.pick(["fmi2GetStatus", "fmi2GetRealStatus", "fmi2GetIntegerStatus",
                          "fmi2GetBooleanStatus", "fmi2GetStringStatus"])
        value = {"fmi2GetStatus": ctypes.c_int, "fmi2GetRealStatus": fmi2Real,
                 "fmi2GetIntegerStatus": fmi2Integer, "fmi2GetBooleanStatus": fmi2Boolean,
                 "fmi2GetStringStatus": fmi2String}[name]()
        kind = int(self.pick([0, 1, 2, 3, 4, -1, 99]))
        status = self.call(name, self.c, kind, ctypes.byref(value))
        if status == 0 and name == "fmi2GetRealStatus" and not math.isfinite(value.value):
            self.violation(f"fmi2GetRealStatus({kind}) returned OK with {value.value}")

    def op_debug_logging(self):
        n = int(self.rng.integers(0, 4))
        cats = [self.pick(LOG_CATEGORIES) for _ in range(n)]
        arr = (fmi2String * max(n, 1))(*cats)
        on = int(self.pick([0, 1, 2]))
        if n and self.rng.random() < 0.1:
            arr = None
        self.call("fmi2SetDebugLogging", self.c, on, n, arr)

    def op_unsupported(self):
        name = self.pick(["fmi2GetDirectionalDerivative", "fmi2SetRealInputDerivatives",
                          "fmi2GetRealOutputDerivatives", "fmi2CancelStep"])
        vr = (fmi2ValueReference * 2)(*self.value_refs(self.reals, 2))
        reals = (fmi2Real * 2)(1.0, float("nan"))
        orders = (fmi2Integer * 2)(1, 2)
        args = {"fmi2GetDirectionalDerivative": (self.c, vr, 2, vr, 2, reals, (fmi2Real * 2)()),
                "fmi2SetRealInputDerivatives": (self.c, vr, 2, orders, reals),
                "fmi2GetRealOutputDerivatives": (self.c, vr, 2, orders, (fmi2Real * 2)()),
                "fmi2CancelStep": (self.c,)}[name]
        if self.call(name, *args) != 3:
            self.violation(f"{name} (not supported) did not return fmi2Error")

    def op_null_instance(self):
        """A NULL fmi2Component: there is no instance to log through, only fmi2Error."""
        name, args = self.pick([
            ("fmi2DoStep", (None, 0.0, 0.01, 1)), ("fmi2Reset", (None,)),
            ("fmi2Terminate", (None,)), ("fmi2EnterInitializationMode", (None,)),
            ("fmi2GetReal", (None, (fmi2ValueReference * 1)(0), 1, (fmi2Real * 1)())),
            ("fmi2SetFMUstate", (None, fmi2FMUstate(self.s0))),
            ("fmi2GetFMUstate", (None, ctypes.byref(fmi2FMUstate()))),
        ])
        if self.call(name, *args, log_required=False) != 3:
            self.violation(f"{name} with a NULL instance did not return fmi2Error")

    def op_reinstantiate(self):
        self.note("fmi2FreeInstance + fmi2Instantiate")
        self.slave.fmi2FreeInstance(self.c)
        self.trace.write(" -> done\n")
        stale = self.states + self.freed
        self.instantiate_fuzzed()
        self.freed = stale[-10:]  # pointers of the freed instance: stale now

    def op_check_reset(self):
        """After fmi2Reset a normal run gives bitwise the fresh instance's outputs."""
        if self.call("fmi2Reset", self.c) != 0:
            self.violation("fmi2Reset did not return OK")
            return
        self.time = 0.0
        self.checked("normal initialise after reset", self.normal_initialise, self.slave)
        out = self.checked(f"{NORMAL_STEPS} normal steps after reset", self.normal_steps, self.slave)
        if out is not None and out != self.expected:
            self.violation("after fmi2Reset, initialise + 10 steps differ from a fresh instance: "
                           + self.first_difference(out))
        self.right_time()

    def op_check_restore(self):
        """After fmi2SetFMUstate(state right after initialisation), 10 steps give bitwise
        the fresh instance's outputs."""
        if self.call("fmi2SetFMUstate", self.c, fmi2FMUstate(self.s0)) != 0:
            self.violation("fmi2SetFMUstate of the state taken after initialisation failed")
            return
        self.time = 0.0
        out = self.checked(f"{NORMAL_STEPS} normal steps after restoring the initial state",
                           self.normal_steps, self.slave)
        if out is not None and out != self.expected:
            self.violation("after fmi2SetFMUstate(initial state), 10 steps differ from a fresh "
                           "instance: " + self.first_difference(out))
        self.right_time()

    def first_difference(self, out):
        names = [self.vars[vr].name for vr in self.reals + self.ints]
        for k, (a, b) in enumerate(zip(out, self.expected)):
            if a != b:
                x = np.frombuffer(a[:8 * len(self.reals)], np.float64)
                y = np.frombuffer(b[:8 * len(self.reals)], np.float64)
                i = next((i for i in range(len(x)) if x[i].tobytes() != y[i].tobytes()), None)
                where = f"{names[i]}: {x[i]!r} vs fresh {y[i]!r}" if i is not None else "integers"
                return f"after step {k}, first at {where}"
        return "lengths differ"

    OPS = [("op_setup", 4), ("op_enter", 4), ("op_exit", 4), ("op_step", 16),
           ("op_get_real", 10), ("op_get_integer", 3), ("op_set_real", 10),
           ("op_set_integer", 3), ("op_bool_string", 2), ("op_terminate", 2), ("op_reset", 3),
           ("op_get_state", 5), ("op_set_state", 5), ("op_free_state", 4), ("op_serialize", 4),
           ("op_deserialize", 6), ("op_status", 4), ("op_debug_logging", 3),
           ("op_unsupported", 2), ("op_null_instance", 1), ("op_reinstantiate", 0.3),
           ("op_check_reset", 1.5), ("op_check_restore", 1.5)]

    def run(self):
        self.reference = self.new_slave(f"ref{self.seed}")
        self.checked("reference: normal setup", self.normal_initialise, self.reference)
        self.expected = self.checked("reference: normal steps", self.normal_steps, self.reference)
        st = fmi2FMUstate()
        self.call("fmi2GetFMUstate", self.reference.component, ctypes.byref(st),
                  slave=self.reference)
        self.foreign = [st.value]
        self.instantiate_fuzzed()
        names = [name for name, _ in self.OPS]
        weights = np.array([w for _, w in self.OPS], dtype=float)
        weights /= weights.sum()
        try:
            for i in range(self.n_calls):
                name = names[int(self.rng.choice(len(names), p=weights))]
                getattr(self, name)()
            self.op_check_reset()
            self.op_check_restore()
        except Violation:
            pass
        self.slave.fmi2FreeInstance(self.c)
        self.reference.fmi2FreeInstance(self.reference.component)


def fuzz_main(fmu, seeds, n_calls, trace_path, result_path):
    """Entry point of the child process: fuzzes one scene's FMU for each seed."""
    unzip = extract(fmu, unzipdir=tempfile.mkdtemp(prefix="rigidfmu-abuse-"))
    result = {"violations": [], "counts": {}, "seconds": {}, "slowest": [], "slow": []}
    try:
        with open(trace_path, "w") as trace:
            for seed in seeds:
                f = Fuzzer(fmu, unzip, seed, n_calls, trace)
                try:
                    f.run()
                except Exception:
                    f.violations.append({"seed": seed, "what": traceback.format_exc(),
                                         "last calls": f.recent})
                result["violations"] += f.violations
                for k, v in f.counts.items():
                    result["counts"][k] = result["counts"].get(k, 0) + v
                for k, v in f.seconds.items():
                    result["seconds"][k] = result["seconds"].get(k, 0.0) + v
                result["slowest"].append((seed,) + f.slowest)
                result["slow"] += f.slow
    finally:
        shutil.rmtree(unzip, ignore_errors=True)
    pathlib.Path(result_path).write_text(json.dumps(result, indent=1))


FUZZ_SEEDS = [11, 22, 33, 44, 55, 66, 77, 88]
FUZZ_CALLS = 400

# Found by a longer run of this fuzzer (seeds 100..140, 800 calls each): the process
# aborts. The call sequence depends on the product's answers, so after a change of the
# FMU this seed may stop reaching the crash (then the strict xfail reports XPASS).
FCL_GJK_ABORT = (
    "Playground, fuzz seed 105, call 800 or so: with sticker.force[3] = -1e308 (finite, accepted by "
    "fmi2SetReal) in a mid-run state where sticker and slider lie side by side on the ramp, "
    "fmi2DoStep of any size (even 1e-300 s) aborts the whole process (SIGABRT): libccd assertion "
    "'A is not in region 1' in fcl::detail::GJKDistance (box-box), called from "
    "rigid::CollisionDetector::Impl::appendWithinMargin <- narrowphase <- detect <- rigid::step. "
    "The bundled libfcl keeps its assertions, and the step hands FCL a configuration produced by "
    "an out-of-range input instead of answering fmi2Discard")


def run_child(code, tmp_path, timeout):
    """A Python child that can import this file (tests/fmu on its PYTHONPATH)."""
    path = os.pathsep.join(p for p in (str(TESTS), os.environ.get("PYTHONPATH")) if p)
    return subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                          text=True, timeout=timeout, env=dict(os.environ, PYTHONPATH=path))


@pytest.mark.parametrize("scene_file,seeds,calls", [
    ("default.json", FUZZ_SEEDS, FUZZ_CALLS),
    ("spinner.json", FUZZ_SEEDS, FUZZ_CALLS),
    ("tumble.json", FUZZ_SEEDS, FUZZ_CALLS),
    ("thruster.json", FUZZ_SEEDS, FUZZ_CALLS),
    # driven bodies and a moving surface; the fuzz's jumps make fast pushes, each
    # sub-stepped: three seeds under the sanitizers, which run it several times slower
    ("pusher.json", FUZZ_SEEDS[:3] if SANITIZED else FUZZ_SEEDS, FUZZ_CALLS),
    ("default-belts.json", FUZZ_SEEDS, FUZZ_CALLS),
    # joints: a motor on a rail, an elastic cable, a hinge with a spring and limits
    ("crane.json", FUZZ_SEEDS[:3] if SANITIZED else FUZZ_SEEDS, FUZZ_CALLS),
    # once aborted the process inside FCL (see FCL_GJK_ABORT); fixed: states beyond 1e12 m
    # or non-finite are refused before collision detection sees them
    pytest.param("default.json", [105], 800, id="default.json-seed105"),
])
def test_fuzzing_the_fmi_calls(fmu_of, scene_file, seeds, calls, tmp_path):
    fmu = fmu_of(FUZZ_SCENES.get(scene_file) or example(scene_file))
    trace, result = tmp_path / "trace.txt", tmp_path / "result.json"
    code = (f"import test_abuse; "
            f"test_abuse.fuzz_main({str(fmu)!r}, {seeds!r}, {calls}, {str(trace)!r}, "
            f"{str(result)!r})")

    def tail():
        lines = trace.read_text(errors="replace").splitlines() if trace.exists() else []
        return "\n".join(lines[-30:])

    try:
        p = run_child(code, tmp_path, timeout=120)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{scene_file}: the fuzzing did not finish in 120 s; last calls "
                    f"(seed first):\n{tail()}")
    assert p.returncode == 0, (
        f"{scene_file}: the fuzzing process died with exit code {p.returncode} "
        f"(a negative code is the signal); stderr:\n{p.stderr[-3000:]}\n"
        f"last calls (seed first, the last one without a status is the one that crashed):\n{tail()}")
    found = json.loads(result.read_text())
    # the fuzzing reached the interesting places
    counts = found["counts"]
    for key in [] if len(seeds) < 3 else ["fmi2DoStep OK", "fmi2DoStep Error", "fmi2DeSerializeFMUstate OK",
                "fmi2DeSerializeFMUstate Error", "fmi2SetFMUstate OK", "fmi2GetReal OK",
                "fmi2SetReal Error", "fmi2Reset OK"]:
        assert counts.get(key, 0) > 0, (key, counts)
    report = "\n\n".join(f"seed {v['seed']}: {v['what']}\n  last calls:\n    " +
                         "\n    ".join(v["last calls"]) for v in found["violations"])
    assert not found["violations"], f"{scene_file}:\n{report}"


GRAVITY_OVERFLOW_CHILD = r"""
from rigidfmu.driver import Slave, status_of
s = Slave({fmu!r})
s.initialize()
s.set_values({{"gravity[3]": -1e308}})  # finite: accepted
print(status_of(lambda: s.slave.doStep(0.0, 1e-3)))
print(s.log.text())
"""


# Found by this file: m g overflowed to -inf and the step ran collision detection on the
# non-finite state (an FCL assertion aborted the process). Now refused as fmi2Discard.
def test_overflowing_gravity_is_a_discard_not_a_crash(fmu_of, tmp_path):
    fmu = fmu_of(PLAYGROUND)
    p = run_child(GRAVITY_OVERFLOW_CHILD.format(fmu=str(fmu)), tmp_path, 60)
    assert p.returncode == 0, f"exit code {p.returncode}: {p.stderr[-1500:]}"
    assert p.stdout.startswith("Discard"), p.stdout
    assert "not finite" in p.stdout


# =====================================================================================
# 2. Threads
# =====================================================================================

def playground_run(fmu, unzip, k, steps=100, h=0.02):
    """One scripted run of the Playground; thread k has its own start values and inputs."""
    s = Slave(fmu, f"thread{k}", unzip_dir=unzip)
    try:
        s.initialize({"gravity[3]": -9.81 + 0.25 * k, "ball.mass": 3.0 + 0.25 * k,
                      "puck.velocity[1]": 4.0 - 0.3 * k, "slider.restitution": 0.1 * (k % 5)})
        trace = []
        blob = None
        for n in range(steps):
            vrs, values = input_signal(s.md, n, phase=0.7 * k, amplitude=1.0 + 0.2 * k)
            s.slave.setReal(vrs, values)
            s.slave.doStep(n * h, h)
            trace.append(outputs(s.slave, s.md))
            if n == steps // 2:
                state = s.slave.getFMUstate()
                blob = bytes(s.slave.serializeFMUstate(state))
                s.slave.freeFMUstate(state)
        return trace, blob
    finally:
        s.close()


def test_eight_instances_in_eight_threads_give_the_serial_results(fmu_of, tmp_path):
    fmu = fmu_of(PLAYGROUND)
    unzip = extract(str(fmu), unzipdir=str(tmp_path / "fmu"))  # one library for all
    serial = {k: playground_run(fmu, unzip, k) for k in range(8)}
    assert len({serial[k][0][-1] for k in range(8)}) == 8  # the threads really differ
    threaded, errors = {}, []
    barrier = threading.Barrier(8)

    def job(k):
        try:
            barrier.wait()
            threaded[k] = playground_run(fmu, unzip, k)
        except BaseException:
            errors.append(traceback.format_exc())

    threads = [threading.Thread(target=job, args=(k,)) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors[0]
    for k in range(8):
        trace, blob = threaded[k]
        first = next((n for n, (a, b) in enumerate(zip(trace, serial[k][0])) if a != b), None)
        assert first is None, f"thread {k} differs from its serial run from step {first}"
        assert blob == serial[k][1], f"thread {k}: the serialised mid-run state differs"


# =====================================================================================
# 3. Determinism across processes
# =====================================================================================

def deterministic_run(fmu, out_path):
    """Child: the Playground with a scripted input signal and a tunable parameter change;
    every output after every step, as hex."""
    s = Slave(fmu, "det")
    try:
        s.initialize()
        rows = [outputs(s.slave, s.md).hex()]
        for n in range(300):
            vrs, values = input_signal(s.md, n)
            s.slave.setReal(vrs, values)
            if n == 150:
                s.set_values({"gravity[1]": 0.5, "gravity[3]": -9.0})
            s.slave.doStep(n * 0.01, 0.01)
            rows.append(outputs(s.slave, s.md).hex())
        pathlib.Path(out_path).write_text(json.dumps(rows))
    finally:
        s.close()


def test_same_inputs_give_bitwise_the_same_outputs_in_two_processes(fmu_of, tmp_path):
    fmu = fmu_of(PLAYGROUND)
    runs = []
    for k in range(2):
        out = tmp_path / f"run{k}.json"
        code = (f"import test_abuse; "
                f"test_abuse.deterministic_run({str(fmu)!r}, {str(out)!r})")
        p = run_child(code, tmp_path, timeout=120)
        assert p.returncode == 0, p.stderr[-3000:]
        runs.append(json.loads(out.read_text()))
    assert len(runs[0]) == 301
    assert runs[0][0] != runs[0][-1]  # something moved
    first = next((n for n, (a, b) in enumerate(zip(*runs)) if a != b), None)
    assert first is None, f"the two processes differ from step {first} on"
    # and the same in this process, where other FMUs are loaded too
    here = tmp_path / "here.json"
    deterministic_run(fmu, here)
    assert json.loads(here.read_text()) == runs[0]


# =====================================================================================
# 4. Leaks and invalid memory accesses under valgrind
# =====================================================================================

DRIVER = r"""
// Instantiate / initialise / step / FMU state / free cycles through dlopen, no Python.
#include <dlfcn.h>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>
#include "fmi2Functions.h"

static int unexpected = 0;
static bool expectError = false;

static void logger(fmi2ComponentEnvironment, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
  if (status == fmi2OK) return;
  if (expectError && status == fmi2Error) return;
  ++unexpected;
  va_list ap;
  va_start(ap, message);
  std::fprintf(stderr, "[status %d] %s %s: ", int(status), name, category);
  std::vfprintf(stderr, message, ap);
  std::fputc('\n', stderr);
  va_end(ap);
}
static void* allocate(size_t n, size_t size) { return std::calloc(n, size); }

#define CHECK(call)                                                     \
  do {                                                                  \
    fmi2Status s_ = (call);                                             \
    if (s_ != fmi2OK) {                                                 \
      std::fprintf(stderr, "cycle %d: %s -> %d\n", k, #call, int(s_));  \
      return 3;                                                         \
    }                                                                   \
  } while (0)

#define LOAD(name)                                                           \
  auto name = reinterpret_cast<name##TYPE*>(dlsym(lib, #name));              \
  if (!name) {                                                               \
    std::fprintf(stderr, "no symbol %s\n", #name);                           \
    return 2;                                                                \
  }

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  const char* so = argv[1];
  const char* guid = argv[2];
  const char* uri = argv[3];
  const int cycles = std::atoi(argv[4]);
  void* lib = dlopen(so, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    std::fprintf(stderr, "dlopen: %s\n", dlerror());
    return 2;
  }
  LOAD(fmi2Instantiate) LOAD(fmi2SetupExperiment) LOAD(fmi2EnterInitializationMode)
  LOAD(fmi2ExitInitializationMode) LOAD(fmi2DoStep) LOAD(fmi2GetFMUstate)
  LOAD(fmi2SetFMUstate) LOAD(fmi2FreeFMUstate) LOAD(fmi2SerializedFMUstateSize)
  LOAD(fmi2SerializeFMUstate) LOAD(fmi2DeSerializeFMUstate) LOAD(fmi2Reset)
  LOAD(fmi2FreeInstance)
  fmi2CallbackFunctions callbacks = {logger, allocate, std::free, nullptr, nullptr};
  for (int k = 0; k < cycles; ++k) {
    // a refused instantiation must not leak either
    expectError = true;
    if (fmi2Instantiate("bad", fmi2CoSimulation, "{not-the-guid}", uri, &callbacks, fmi2False,
                        fmi2False)) {
      std::fprintf(stderr, "a wrong GUID was accepted\n");
      return 4;
    }
    expectError = false;
    fmi2Component c =
        fmi2Instantiate("leak", fmi2CoSimulation, guid, uri, &callbacks, fmi2False, fmi2False);
    if (!c) {
      std::fprintf(stderr, "cycle %d: fmi2Instantiate failed\n", k);
      return 3;
    }
    CHECK(fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    CHECK(fmi2EnterInitializationMode(c));
    CHECK(fmi2ExitInitializationMode(c));
    fmi2FMUstate kept = nullptr, loaded = nullptr;
    CHECK(fmi2GetFMUstate(c, &kept));
    for (int n = 0; n < 3; ++n) CHECK(fmi2DoStep(c, n * 0.005, 0.005, fmi2True));
    size_t size = 0;
    CHECK(fmi2SerializedFMUstateSize(c, kept, &size));
    std::vector<fmi2Byte> bytes(size);
    CHECK(fmi2SerializeFMUstate(c, kept, bytes.data(), size));
    CHECK(fmi2DeSerializeFMUstate(c, bytes.data(), size, &loaded));
    CHECK(fmi2SetFMUstate(c, loaded));
    CHECK(fmi2DoStep(c, 0.0, 0.005, fmi2True));
    // odd cycles free their states, even ones leave them to fmi2FreeInstance
    if (k % 2) {
      CHECK(fmi2FreeFMUstate(c, &kept));
      CHECK(fmi2FreeFMUstate(c, &loaded));
    }
    if (k % 3 == 0) CHECK(fmi2Reset(c));
    fmi2FreeInstance(c);
  }
  // the library stays loaded, as in an importer that keeps it for the next instance
  std::printf("%d cycles, %d unexpected messages\n", cycles, unexpected);
  return unexpected ? 5 : 0;
}
"""


@pytest.fixture(scope="module")
def driver(tmp_path_factory):
    if not shutil.which("g++"):
        pytest.skip("g++ is not on PATH")
    import fmpy
    headers = pathlib.Path(fmpy.__file__).parent / "c-code"
    d = tmp_path_factory.mktemp("driver")
    (d / "driver.cpp").write_text(DRIVER)
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}  # not for the compiler
    subprocess.run(["g++", "-std=c++17", "-O1", "-g", "-I", str(headers), str(d / "driver.cpp"),
                    "-o", str(d / "driver"), "-ldl"], check=True, env=env)
    return d / "driver"


def driver_args(fmu, unzip):
    md = read_model_description(str(fmu))
    so = pathlib.Path(unzip, "binaries", "linux64", md.coSimulation.modelIdentifier + ".so")
    return [str(so), md.guid, pathlib.Path(unzip, "resources").as_uri()]


LEAK_SCENES = ["spinner.json", "default.json"]


@pytest.mark.parametrize("scene_file", LEAK_SCENES)
def test_a_thousand_cycles_without_valgrind(fmu_of, driver, scene_file, tmp_path):
    """The driver itself, natively: 1000 cycles of every call, all OK. In the sanitizer
    run (scripts/sanitize.sh) the same 1000 cycles run under ASan/UBSan with
    LeakSanitizer on: any leak, invalid access or undefined behaviour fails."""
    fmu = fmu_of(example(scene_file))
    unzip = extract(str(fmu), unzipdir=str(tmp_path / "fmu"))
    env = dict(os.environ)
    if SANITIZED:
        env["ASAN_OPTIONS"] = "halt_on_error=1:detect_leaks=1"
    p = subprocess.run([str(driver)] + driver_args(fmu, unzip) + ["1000"], capture_output=True,
                       text=True, timeout=600 if SANITIZED else 120, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "1000 cycles" in p.stdout


# glibc's loader, not the FMU: while dlopen expands the bundled libraries' RUNPATH
# "$ORIGIN", its word-wise strncmp (is_dst) reads past the 8-byte string "$ORIGIN", which
# memcheck reports as "Invalid read of size 8" inside ld.so.
LD_SO_SUPPRESSION = """
{
   ld.so-is_dst-strncmp-reads-whole-words
   Memcheck:Addr8
   fun:strncmp
   fun:is_dst
   ...
}
"""

# The 1000 cycles, under valgrind too (~0.1 s a cycle for the Playground).
VALGRIND_CYCLES = 1000


@pytest.mark.skipif(not shutil.which("valgrind"), reason="valgrind is not on PATH")
@pytest.mark.skipif(SANITIZED, reason="valgrind does not run beside ASan (LeakSanitizer checks instead)")
@pytest.mark.parametrize("scene_file", LEAK_SCENES)
def test_no_leaks_and_no_invalid_accesses_under_valgrind(fmu_of, driver, scene_file, tmp_path):
    fmu = fmu_of(example(scene_file))
    unzip = extract(str(fmu), unzipdir=str(tmp_path / "fmu"))
    log = tmp_path / "valgrind.log"
    supp = tmp_path / "ld.so.supp"
    supp.write_text(LD_SO_SUPPRESSION)
    cmd = ["valgrind", "--leak-check=full", "--errors-for-leak-kinds=definite",
           "--error-exitcode=99", f"--suppressions={supp}", f"--log-file={log}", str(driver)]
    p = subprocess.run(cmd + driver_args(fmu, unzip) + [str(VALGRIND_CYCLES)],
                       capture_output=True, text=True, timeout=900)
    report = log.read_text(errors="replace") if log.exists() else ""
    assert p.returncode == 0, (f"exit code {p.returncode} (99: valgrind found errors)\n"
                               f"{p.stdout}{p.stderr}\n{report[-6000:]}")
    assert f"{VALGRIND_CYCLES} cycles" in p.stdout
    assert "definitely lost: 0 bytes" in report or "All heap blocks were freed" in report, \
        report[-3000:]
    assert "Invalid read" not in report and "Invalid write" not in report, report[-6000:]
