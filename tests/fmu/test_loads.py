"""Forces at load points through the FMU (issue 18): the example scene's load inputs
are named b.LOAD.force[i] with units and descriptions; a body-frame force at the rim of
a spinning disc spins it up at the closed-form rate, also with input derivatives."""
import json
import pathlib

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from harness import Slave

ROOT = pathlib.Path(__file__).resolve().parents[2]
R, M, W0 = 0.5, 2.0, 3.0  # m, kg, rad/s: the disc
I = 0.5 * M * R ** 2


def disc():
    return {"name": "RimDisc", "gravity": [0, 0, 0], "solver": {"method": "rk4", "step": 1e-3},
            "bodies": [{"name": "disc", "shape": {"type": "cylinder", "radius": R, "length": 0.1}, "mass": M,
                        "angularVelocity": [0, 0, W0],
                        "loads": [{"name": "rim", "point": [R, 0, 0], "frame": "body"}]}]}


def test_the_example_scenes_loads_are_inputs_with_units_and_descriptions(fmu_of):
    fmu = fmu_of(json.loads((ROOT / "scripts" / "scenes" / "thruster.json").read_text()))
    assert validate_fmu(str(fmu)) == []
    variables = {v.name: v for v in read_model_description(str(fmu)).modelVariables}
    for load, frame in (("thruster", "body"), ("tether", "world")):
        for i in (1, 2, 3):
            v = variables[f"rocket.{load}.force[{i}]"]
            assert (v.causality, v.variability, v.unit) == ("input", "continuous", "N")
            assert f"in the {frame} frame" in v.description
    # the scene asked for no force or torque input at the centre of mass
    assert "rocket.force[1]" not in variables and "rocket.torque[1]" not in variables


def test_a_follower_force_at_the_rim_spins_the_disc_up(fmu_of):
    """F = 0.8 N tangential in the body frame at r: omega = w0 + F r t / I, I = m r^2 / 2;
    then with a derivative dF/dt = 2 N/s over one step of 0.5 s: + r (F h + h^2) / I."""
    F, T = 0.8, 1.0
    s = Slave(fmu_of(disc()))
    try:
        s.initialize()
        s.set_values({"disc.rim.force[2]": F})
        for k in range(10):
            s.slave.doStep(0.1 * k, 0.1)
        w = s.get("disc.angularVelocity[3]")
        assert w == pytest.approx(W0 + F * R * T / I, rel=1e-9)
        h, rate = 0.5, 2.0
        s.slave.setRealInputDerivatives(s.vr(["disc.rim.force[2]"]), [1], [rate])
        s.slave.doStep(T, h)
        assert s.get("disc.angularVelocity[3]") == pytest.approx(w + R * (F * h + 0.5 * rate * h * h) / I, rel=1e-9)
        assert s.get("disc.rim.force[2]") == F  # the input is again the value set
    finally:
        s.close()
