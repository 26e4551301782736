"""A small reader of the SSP 1.0 system structure (system.ssd) that the systems use:
the components and their FMUs, the connections from output to input, the parameter
values bound inline, the start and stop time, and the communication step from the
Open Simulation Platform's annotation (osp:FixedStepAlgorithm baseStepSize), which
libcosim reads too. Anything else in the file is left to the master."""
import pathlib
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
}
NANOSECONDS = 1_000_000_000  # libcosim's time unit: a step is a whole number of them


class SsdError(ValueError):
    """A system.ssd that this reader cannot run: the message names the element."""


@dataclass(frozen=True)
class Connection:
    source: str  # component
    output: str  # its variable
    target: str
    input: str


@dataclass
class System:
    path: pathlib.Path
    name: str
    components: dict[str, str]  # name -> FMU file (relative to the SSD)
    connections: list[Connection]
    parameters: dict[str, dict[str, float]] = field(default_factory=dict)  # component -> name -> value
    start: float = 0.0
    stop: float = 0.0
    step_ns: int = 0  # the communication step in ns

    @property
    def step(self) -> float:
        return self.step_ns / NANOSECONDS

    @property
    def steps(self) -> int:
        """Communication steps from start to stop."""
        return round((self.stop - self.start) * NANOSECONDS) // self.step_ns

    def parameter(self, reference: str) -> float:
        """The value bound to 'component.name' in the SSD."""
        component, _, name = reference.partition(".")
        try:
            return self.parameters[component][name]
        except KeyError:
            raise SsdError(f"{self.path}: no parameter {name} bound to component {component}") from None


def _attribute(element, name, where):
    value = element.get(name)
    if value is None:
        raise SsdError(f"{where}: <{element.tag.split('}')[-1]}> has no {name}")
    return value


def _parameters(component) -> dict[str, float]:
    values = {}
    for p in component.findall("ssd:ParameterBindings/ssd:ParameterBinding/ssd:ParameterValues/"
                               "ssv:ParameterSet/ssv:Parameters/ssv:Parameter", NS):
        real = p.find("ssv:Real", NS)
        if real is not None:
            values[p.get("name")] = float(real.get("value"))
    return values


def _experiment(root, path):
    experiment = root.find("ssd:DefaultExperiment", NS)
    if experiment is None or experiment.get("stopTime") is None:
        raise SsdError(f"{path}: needs <ssd:DefaultExperiment stopTime=...>")
    algorithm = experiment.find(".//osp:FixedStepAlgorithm", NS)
    if algorithm is None:
        raise SsdError(f"{path}: needs the communication step, <osp:FixedStepAlgorithm baseStepSize=...> "
                           "in the DefaultExperiment's annotation")
    step_ns = round(float(_attribute(algorithm, "baseStepSize", path)) * NANOSECONDS)
    if step_ns <= 0:
        raise SsdError(f"{path}: baseStepSize must be at least 1 ns")
    return float(experiment.get("startTime", "0")), float(experiment.get("stopTime")), step_ns


def read(path) -> System:
    """The system of an SSD file (system.ssd) or of the folder that holds one."""
    path = pathlib.Path(path)
    if path.is_dir():
        path = path / "system.ssd"
    root = ET.parse(path).getroot()
    system = root.find("ssd:System", NS)
    if system is None:
        raise SsdError(f"{path}: no <ssd:System>")
    components, parameters = {}, {}
    for c in system.findall("ssd:Elements/ssd:Component", NS):
        name = _attribute(c, "name", path)
        components[name] = _attribute(c, "source", path)
        parameters[name] = _parameters(c)
    connections = []
    for c in system.findall("ssd:Connections/ssd:Connection", NS):
        connection = Connection(*(_attribute(c, a, path) for a in ("startElement", "startConnector", "endElement",
                                                                    "endConnector")))
        for component in (connection.source, connection.target):
            if component not in components:
                raise SsdError(f"{path}: a connection names component {component}, which is not an element")
        connections.append(connection)
    start, stop, step_ns = _experiment(root, path)
    return System(path, root.get("name", system.get("name", path.parent.name)), components, connections, parameters,
                  start, stop, step_ns)
