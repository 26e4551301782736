"""The errors the command line reports as a message and exit status 1 (no traceback):
the user's input or the machine is at fault, not the code."""


class RigidfmuError(Exception):
    """Base of the errors below."""


class SceneError(RigidfmuError, ValueError):
    """The scene breaks a rule of the scene format (the message names the field)."""


class PackagingError(RigidfmuError):
    """The FMU could not be put together (a missing binary or tool)."""


class NativeError(RigidfmuError):
    """The core's binaries are missing or could not be built."""


class ReplayError(RigidfmuError):
    """The replay page's template is missing and cannot be built here."""


class SimulationError(RigidfmuError):
    """The FMU refused a call during a simulation."""


class StudyError(RigidfmuError, ValueError):
    """A study file breaks a rule of the study format (the message names the field)."""


class ReportError(RigidfmuError):
    """A report cannot be made here (no core to build it from, a scene it cannot use)."""
