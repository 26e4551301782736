"""Timing an FMU's steps through fmpy, shared by the benchmark scripts."""
import statistics
import time

from rigidfmu.driver import Slave


def seconds_per_internal_step(fmu, communication_step, calls, repeats):
    """Median over `repeats` runs of `calls` fmi2DoStep calls of `communication_step`
    seconds each, divided by the internal steps they hold (solver.step from the
    DefaultExperiment)."""
    s = Slave(fmu, "timing", recorder=False)
    s.initialize()
    internal = round(communication_step / float(s.md.defaultExperiment.stepSize))
    t, runs = 0.0, []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(calls):
            s.slave.doStep(t, communication_step)
            t += communication_step
        runs.append((time.perf_counter() - start) / (calls * internal))
    s.slave.terminate()
    s.free()
    s.model.close()
    return statistics.median(runs)
