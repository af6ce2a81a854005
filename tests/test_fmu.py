"""tirefe_tire.fmu: its modelDescription.xml is a well-formed FMI 2.0 co-simulation
description, its archive holds what it names, its binary exports the fmi2 functions only,
and a host that loads it with dlopen and drives it through the FMI functions alone
(tests/fmu_host.c) gets the spindle force and stiffness of the C API, repeats a stretch
from a saved FMU state bit for bit, and sees an impossible step discarded.

    test_fmu.py TIREFE_TIRE_FMU    (FMU_HOST names the host, PRESS_TIRE the C API twin)
"""
import os
import re
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import script_tests

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# FMI 2.0 (section 2.2.7): the legal causality / variability pairs, and which need a start.
LEGAL = {
    ("parameter", "fixed"), ("parameter", "tunable"),
    ("calculatedParameter", "fixed"), ("calculatedParameter", "tunable"),
    ("input", "discrete"), ("input", "continuous"),
    ("output", "constant"), ("output", "discrete"), ("output", "continuous"),
    ("local", "constant"), ("local", "fixed"), ("local", "tunable"), ("local", "discrete"), ("local", "continuous"),
    ("independent", "continuous"),
}
TYPES = {"Real", "Integer", "Boolean", "String", "Enumeration"}


def description():
    with zipfile.ZipFile(TIREFE) as archive:
        return ET.fromstring(archive.read("modelDescription.xml"))


def test_model_description(folder):
    root = description()
    assert root.tag == "fmiModelDescription" and root.get("fmiVersion") == "2.0", root.attrib
    for attribute in ("modelName", "guid"):
        assert root.get(attribute), attribute
    assert re.fullmatch(r"\{[0-9a-f-]{36}\}", root.get("guid")), root.get("guid")
    cosimulation = root.find("CoSimulation")
    assert cosimulation is not None and cosimulation.get("modelIdentifier") == "tirefe_tire"
    assert cosimulation.get("canGetAndSetFMUstate") == "true"
    assert cosimulation.get("providesDirectionalDerivative") == "true"
    assert root.find("ModelExchange") is None
    variables = root.find("ModelVariables").findall("ScalarVariable")
    references, names = set(), set()
    for variable in variables:
        name, reference = variable.get("name"), variable.get("valueReference")
        assert name and reference is not None, variable.attrib
        assert name not in names, f"name {name} twice"
        names.add(name)
        types = [child.tag for child in variable if child.tag in TYPES]
        assert len(types) == 1, (name, types)
        key = (types[0], int(reference))
        assert key not in references, f"valueReference {reference} twice for {types[0]}"
        references.add(key)
        causality = variable.get("causality", "local")
        variability = variable.get("variability", "continuous")
        assert (causality, variability) in LEGAL, (name, causality, variability)
        if types[0] != "Real":
            assert variability != "continuous", name
        start = variable.find(types[0]).get("start")
        if causality in ("parameter", "input"):
            assert start is not None, f"{name} ({causality}) needs a start value"
        if causality == "output":
            assert start is None, f"{name}: a calculated output has no start value"
    by_index = {i + 1: v for i, v in enumerate(variables)}
    outputs = [i for i, v in by_index.items() if v.get("causality") == "output"]
    structure = root.find("ModelStructure")
    listed = [int(u.get("index")) for u in structure.find("Outputs").findall("Unknown")]
    assert listed == outputs, (listed, outputs)
    for unknown in structure.find("Outputs").findall("Unknown"):
        for index in unknown.get("dependencies", "").split():
            assert by_index[int(index)].get("causality") == "input", index
    initial = [int(u.get("index")) for u in structure.find("InitialUnknowns").findall("Unknown")]
    assert initial == outputs, initial
    # The spindle speaks ISO 8855 wheel axes, as the C API does (docs/coupling.md).
    by_causality = lambda causality: [v.get("name") for v in variables if v.get("causality") == causality]
    assert by_causality("input") == ["x", "z", "spin"], by_causality("input")
    assert by_causality("output") == ["Fx", "Fz", "My"], by_causality("output")
    assert "Fz = +load" in by_index[outputs[1]].get("description"), by_index[outputs[1]].attrib


def test_parameters_start_at_the_shipped_tire(folder):
    with open(os.path.join(SOURCE, "inputs/tires/145SR12.tir")) as f:
        tir = f.read()
    # The keys' comments name the model:tire parameter: "= 100   $ k_sw: ...".
    shipped = {name: r"=\s*(\S+)\s*\$ " + name + ":" for name in ("pressure", "k_sw")}
    starts = {v.get("name"): v.find("Real") for v in description().find("ModelVariables")}
    for name, pattern in shipped.items():
        value = float(re.search(pattern, tir).group(1))
        assert float(starts[name].get("start")) == value, (name, starts[name].get("start"), value)


def test_archive_is_self_contained(folder):
    with zipfile.ZipFile(TIREFE) as archive:
        names = set(archive.namelist())
    for name in ("modelDescription.xml", "binaries/linux64/tirefe_tire.so", "resources/145SR12.tir",
                 "resources/lua/tire_on_road.lua", "resources/lua/tires/145SR12.lua"):
        assert name in names, name


def test_exports_fmi2_only(folder):
    unpacked = os.path.join(folder, "fmu")
    subprocess.run(["cmake", "-E", "make_directory", unpacked], check=True)
    subprocess.run(["cmake", "-E", "tar", "xf", TIREFE], cwd=unpacked, check=True)
    symbols = subprocess.run(["nm", "-D", "--defined-only", os.path.join(unpacked, "binaries/linux64/tirefe_tire.so")],
                             capture_output=True, text=True, check=True).stdout.split("\n")
    exported = [line.split()[-1] for line in symbols if line.strip() and line.split()[1] in "TDBRW"]
    assert exported and all(name.startswith("fmi2") for name in exported), [n for n in exported if not n.startswith("fmi2")]
    assert "fmi2DoStep" in exported and "fmi2GetDirectionalDerivative" in exported


def values(output):
    return {key: float(value) for key, value in (line.split() for line in output.splitlines())}


def test_driven_through_fmi(folder):
    unpacked = os.path.join(folder, "fmu")
    env = dict(os.environ)
    env.pop("TIREFE_LUA_PATH", None)
    host = subprocess.run([os.environ["FMU_HOST"], unpacked], capture_output=True, text=True, env=env, timeout=100)
    assert host.returncode == 0, host.stderr
    got = values(host.stdout)
    reference = values(subprocess.run([os.environ["PRESS_TIRE"]], capture_output=True, text=True, check=True).stdout)
    for key in ("Fz", "H_zz"):
        assert abs(got[key] - reference[key]) <= 1e-9 * abs(reference[key]), (key, got[key], reference[key])
    # ISO wheel axes: the pressed tire carries the wheel (Fz > 0) and lifting it unloads it;
    # the directional derivative is the slope of the FMU's own Fz to 1e-5 (differences of
    # +-1e-7 m around a 5 mm press).
    assert got["Fz"] > 0 and got["H_zz"] < 0, got
    assert abs(got["H_zz_fd"] - got["H_zz"]) <= 1e-5 * abs(got["H_zz"]), got
    assert got["repeat"] == 1, "a stretch repeated from a saved FMU state differs"
    assert got["discard"] == 1, "an impossible step was not discarded with the FMU left as it was"
    assert "[tire, status 2]" in host.stderr, host.stderr  # fmi2Discard, logged with its reason


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_fmu_")
