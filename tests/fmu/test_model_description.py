"""Every FMU built from the repository's scenes passes fmpy's validation, and the
modelDescription.xml agrees with the binary it ships with."""
import pathlib

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

import scenes
from harness import Slave

ROOT = pathlib.Path(__file__).resolve().parents[2]
REPO_SCENES = sorted((ROOT / "scripts" / "scenes").glob("*.json"))
TEST_SCENES = {"projectile": scenes.projectile(), "spin": scenes.free_spin(),
               "two_bodies": scenes.two_bodies()}


@pytest.mark.parametrize("scene_file", REPO_SCENES, ids=[p.stem for p in REPO_SCENES])
def test_repository_scene_fmu_validates(scene_file, fmu_of):
    fmu = fmu_of(scene_file)
    assert validate_fmu(str(fmu)) == []


@pytest.mark.parametrize("name", sorted(TEST_SCENES))
def test_test_scene_fmu_validates(name, fmu_of):
    assert validate_fmu(str(fmu_of(TEST_SCENES[name]))) == []


def test_every_variable_has_unit_or_enumeration_type_and_description(fmu_of):
    md = read_model_description(str(fmu_of(scenes.two_bodies())))
    units = {u.name for u in md.unitDefinitions}
    for v in md.modelVariables:
        assert v.description, v.name
        if v.type == "Real":
            assert v.unit in units, v.name
        elif v.type == "Integer":  # FMI 2.0 Integers carry no unit: counts
            assert v.name.endswith((".contacts", "solver.steps")) and v.causality == "output", v.name
        else:
            assert v.type == "Enumeration" and v.declaredType.name == "SolverMethod", v.name
    assert [(i.name, int(i.value)) for i in md.typeDefinitions[0].items] == [
        ("euler", 1), ("rk4", 2), ("symplecticEuler", 3), ("splitting", 4), ("lieRk4", 5), ("dopri5", 6),
        ("rosenbrock", 7)]


def test_contract_variable_names(fmu_of):
    md = read_model_description(str(fmu_of(scenes.two_bodies())))
    names = {v.name for v in md.modelVariables}
    expected = {"gravity[1]", "gravity[2]", "gravity[3]", "solver.method", "solver.step"}
    for b in ("a", "b"):
        expected |= {f"{b}.mass", f"{b}.restitution"}
        for field, n in [("position", 3), ("orientation", 4), ("velocity", 3),
                         ("angularVelocity", 3), ("linearMomentum", 3), ("angularMomentum", 3),
                         ("force", 3), ("torque", 3)]:
            expected |= {f"{b}.{field}[{i}]" for i in range(1, n + 1)}
    assert expected <= names
    causality = {v.name: v.causality for v in md.modelVariables}
    assert causality["a.force[1]"] == "input" and causality["a.torque[3]"] == "input"
    assert causality["a.position[1]"] == "output" and causality["b.angularMomentum[2]"] == "output"
    assert causality["a.mass"] == "parameter" and causality["gravity[2]"] == "parameter"
    assert {v.name: v.variability for v in md.modelVariables}["gravity[1]"] == "tunable"
    assert md.coSimulation.canGetAndSetFMUstate is True and md.coSimulation.canSerializeFMUstate is True


def test_guid_derives_from_scene_content(fmu_of):
    a = scenes.projectile()
    b = scenes.projectile()
    b["bodies"][0]["mass"] = 1.5
    guid_a = read_model_description(str(fmu_of(a))).guid
    assert guid_a == read_model_description(str(fmu_of(scenes.projectile()))).guid
    assert guid_a != read_model_description(str(fmu_of(b))).guid


def test_binary_start_values_equal_xml_start_values(fmu_of):
    """Importers do not push start values: what the binary holds must be what the XML says."""
    fmu = fmu_of(scenes.two_bodies())
    s = Slave(fmu)
    try:
        s.slave.setupExperiment(startTime=0.0)
        s.slave.enterInitializationMode()
        for v in s.md.modelVariables:
            if v.start is None:
                continue
            if v.type == "Real":
                assert s.slave.getReal([v.valueReference])[0] == float(v.start), v.name
            else:
                assert s.slave.getInteger([v.valueReference])[0] == int(v.start), v.name
        # the scene's values, by name: the XML's value references address the right fields
        assert s.get("a.position[2]", "b.velocity[3]", "a.orientation[4]") == [-2.5, 9.0, 0.5]
        assert s.get("b.mass", "a.restitution", "gravity[1]", "solver.step") == [0.75, 0.7, 0.5, 2e-3]
        assert s.slave.getInteger(s.vr(["solver.method"])) == [1]
        # calculated initial unknowns follow from the exact ones: P = M V
        P = np.array(s.get("b.linearMomentum[1]", "b.linearMomentum[2]", "b.linearMomentum[3]"))
        np.testing.assert_allclose(P, 0.75 * np.array([7.0, -8.0, 9.0]), rtol=1e-15)
    finally:
        s.close()
