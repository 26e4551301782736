"""rigidfmu: a rigid-body world compiled, one scene at a time, into an FMI 2.0
Co-Simulation FMU.

The package holds what surrounds the C++ core: building a scene's FMU
(rigidfmu.fmu_package), locating the core's binaries (rigidfmu.native) and the
command line (rigidfmu.cli, installed as the `rigidfmu` command).
"""

__version__ = "0.1.0"
