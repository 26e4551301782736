"""Timing an FMU's steps through fmpy, shared by the benchmark scripts."""
import statistics
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def seconds_per_internal_step(fmu, communication_step, calls, repeats):
    """Median over `repeats` runs of `calls` fmi2DoStep calls of `communication_step`
    seconds each, divided by the internal steps they hold (solver.step from the
    DefaultExperiment)."""
    md = read_model_description(str(fmu))
    slave = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)),
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName="timing")
    slave.instantiate()
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    internal = round(communication_step / float(md.defaultExperiment.stepSize))
    t, runs = 0.0, []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(calls):
            slave.doStep(t, communication_step)
            t += communication_step
        runs.append((time.perf_counter() - start) / (calls * internal))
    slave.terminate()
    slave.freeInstance()
    return statistics.median(runs)
