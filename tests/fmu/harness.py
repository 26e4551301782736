"""The tests' names for the FMU driver (rigidfmu.driver): a logger that records messages,
value access by variable name, the standard call sequence."""
from rigidfmu.driver import STATUS, Recorder, Slave, status_of  # noqa: F401
