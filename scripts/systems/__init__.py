"""Example systems of FMUs, run in a real co-simulation master (docs/guide/systems.md).

A system is a folder `scripts/systems/NAME/` that holds

    system.ssd      the FMUs and their connections (SSP 1.0); its DefaultExperiment gives
                    the stop time and, in the Open Simulation Platform's annotation, the
                    communication step
    outcome.json    what must hold at the end, in bands (outcome.py)
    X.json          the scene of a component whose source is X.fmu (rigidfmu build)
    X/              the C source and modelDescription.xml of a component X.fmu (fmus.py):
                    a sampled controller's model, built with the FMI functions of
                    sampled_fmu/, which every controller shares

`./scripts/system.sh scripts/systems/NAME` builds the FMUs (fmus.py), runs the system
in libcosim (masters.py), checks the outcome (outcome.py) and exits 0 only when it
holds; `--master fmpy` runs the same SSD in fmpy, `--master both` in both and compares
them value for value.
"""
