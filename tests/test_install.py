"""The installed tirefe as a host project uses it: `cmake --install` into a temporary
prefix, a small C host (tests/install/press_tire.c) built against it with pkg-config and
with find_package(tirefe), run from the prefix and from a moved copy of it, each giving the
spindle force of the build tree's own copy of the host; the Lua modules found next to the
library, through TIREFE_LUA_PATH, and a clear error when they are missing.

    test_install.py TIREFE    (the build tree's tirefe; PRESS_TIRE names its press_tire)
"""
import base64
import glob
import hashlib
import os
import re
import shutil
import subprocess

import script_tests

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RELATIVE = 1e-9  # the same code on the same numbers: equal up to rounding of the output


def run(command, env=None, check=True):
    result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)
    if check and result.returncode != 0:
        raise AssertionError(f"{command} failed ({result.returncode}):\n{result.stdout}\n{result.stderr}")
    return result


def forces(output):
    """{'Fz': ..., 'H_zz': ...} from press_tire's output."""
    return {key: float(value) for key, value in (line.split() for line in output.splitlines())}


def host_env(prefix):
    """The environment of a host run from 'prefix': its library path, no module path."""
    env = dict(os.environ)
    env.pop("TIREFE_LUA_PATH", None)
    env["LD_LIBRARY_PATH"] = os.path.join(prefix, "lib")
    return env


def check_same(output, reference):
    got, expected = forces(output), forces(reference)
    for key in expected:
        assert abs(got[key] - expected[key]) <= RELATIVE * abs(expected[key]), (key, got[key], expected[key])


def reference():
    return run([os.environ["PRESS_TIRE"]]).stdout


def test_install_layout(folder):
    prefix = os.path.join(folder, "prefix")
    run(["cmake", "--install", os.path.dirname(TIREFE), "--prefix", prefix])
    for path in ["bin/tirefe", "include/tirefe.h", "lib/libtirefe.so", "lib/pkgconfig/tirefe.pc",
                 "lib/cmake/tirefe/tirefeConfig.cmake", "share/tirefe/lua/tire_on_road.lua",
                 "share/tirefe/lua/tires/145SR12.lua", "share/tirefe/tires/145SR12.tir",
                 "share/tirefe/tirefe_tire.fmu"]:
        assert os.path.exists(os.path.join(prefix, path)), path
    soname = run(["objdump", "-p", os.path.join(prefix, "lib/libtirefe.so")]).stdout
    assert "SONAME               libtirefe.so.0" in soname, soname
    assert os.path.islink(os.path.join(prefix, "lib/libtirefe.so.0"))


def test_pkg_config_host(folder):
    prefix = os.path.join(folder, "prefix")
    env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(prefix, "lib/pkgconfig"))
    flags = run(["pkg-config", "--cflags", "--libs", "tirefe"], env=env).stdout.split()
    host = os.path.join(folder, "press_tire_pkg")
    run(["cc", "-std=c99", "-Wall", "-Werror", os.path.join(SOURCE, "tests/install/press_tire.c"), "-o", host] + flags)
    check_same(run([host], env=host_env(prefix)).stdout, reference())


def test_find_package_host(folder):
    prefix = os.path.join(folder, "prefix")
    build = os.path.join(folder, "consumer")
    run(["cmake", "-S", os.path.join(SOURCE, "tests/install"), "-B", build, f"-DCMAKE_PREFIX_PATH={prefix}",
         "-DCMAKE_SKIP_RPATH=ON"])
    run(["cmake", "--build", build])
    check_same(run([os.path.join(build, "press_tire")], env=host_env(prefix)).stdout, reference())


def test_moved_prefix(folder):
    moved = os.path.join(folder, "moved")
    shutil.move(os.path.join(folder, "prefix"), moved)
    host = os.path.join(folder, "consumer", "press_tire")
    check_same(run([host], env=host_env(moved)).stdout, reference())
    installed = run([os.path.join(moved, "bin/tirefe"), "--version"])
    assert installed.stdout.startswith("tirefe "), installed.stdout


def installed_packages(prefix):
    """The folder of the installed tirefe package under 'prefix' (lib/python3.X/dist-packages)."""
    found = glob.glob(os.path.join(prefix, "lib", "python3*", "dist-packages", "tirefe", "__init__.py"))
    assert len(found) == 1, found
    return os.path.dirname(os.path.dirname(found[0]))


def test_python_module(folder):
    """The installed package imports from the moved prefix and finds its library and modules."""
    if not os.path.isdir(os.path.join(os.path.dirname(TIREFE), "python")):
        return  # built without pybind11
    env = dict(os.environ, PYTHONPATH=installed_packages(os.path.join(folder, "moved")))
    env.pop("TIREFE_LUA_PATH", None)
    script = ("import tirefe\n"
              "t = tirefe.Tire('tires.145SR12', {'pressure': 180e3})\n"
              "for k in range(1, 121):\n"
              "    s = min(k / 100.0, 1.0)\n"
              "    f, j = t.solve(1e-3, 0.0, -0.005 * s * s * (3 - 2 * s))\n"
              "    t.commit()\n"
              "print(f'Fz {f[1]!r}\\nH_zz {j[1, 1]!r}')\n")
    check_same(run(["/usr/bin/python3", "-c", script], env=env).stdout, reference())


def test_python_package_where_debian_looks(folder):
    """`cmake --install` with the prefixes Debian's python3 knows (/usr/local, the default,
    and /usr; staged with DESTDIR) puts the package into a folder of its site.getsitepackages(),
    with the distribution's metadata (the PEP 440 version of tirefe.__version__, numpy
    required, a RECORD of every file with its sha256), type stubs and py.typed."""
    if not os.path.isdir(os.path.join(os.path.dirname(TIREFE), "python")):
        return  # built without pybind11
    site = run(["/usr/bin/python3", "-c", "import site; print('\\n'.join(site.getsitepackages()))"]).stdout.split()
    for prefix in ("/usr/local", "/usr"):
        stage = os.path.join(folder, "stage" + prefix.replace("/", "_"))
        run(["cmake", "--install", os.path.dirname(TIREFE), "--prefix", prefix], env=dict(os.environ, DESTDIR=stage))
        packages = installed_packages(stage + prefix)
        assert packages[len(stage):] in site, (packages[len(stage):], site)
        for name in ("__init__.py", "fmu.py", "_core.pyi", "py.typed"):
            assert os.path.isfile(os.path.join(packages, "tirefe", name)), name
        env = dict(os.environ, PYTHONPATH=packages)
        env.pop("TIREFE_LUA_PATH", None)
        script = ("import importlib.metadata as m, tirefe\n"
                  "print(tirefe.__version__, m.version('tirefe'), m.requires('tirefe'))\n"
                  "print(tirefe.static_forces('tires.145SR12', {}, [0.01])[0])\n"
                  "for f in m.files('tirefe'): print('file', f, f.hash.value if f.hash else '-')\n")
        lines = run(["/usr/bin/python3", "-c", script], env=env).stdout.splitlines()
        version, metadata_version, requires = lines[0].split(" ", 2)
        assert version == metadata_version and requires == "['numpy']", lines[0]
        assert re.fullmatch(r"\d+(\.\d+)*(\+g[0-9a-f]+)?", version), version  # PEP 440, a local label
        assert 1000 < float(lines[1]) < 2500, lines[1]  # 10 mm: about 1.7 kN
        recorded = {line.split()[1]: line.split()[2] for line in lines[2:]}
        assert "tirefe/_core.pyi" in recorded and any(f.startswith("tirefe/_core.cpython") for f in recorded), recorded
        with open(os.path.join(packages, "tirefe", "fmu.py"), "rb") as f:
            digest = base64.urlsafe_b64encode(hashlib.sha256(f.read()).digest()).rstrip(b"=").decode()
        assert recorded["tirefe/fmu.py"] == digest, recorded["tirefe/fmu.py"]


def test_lua_path(folder):
    moved = os.path.join(folder, "moved")
    modules = os.path.join(folder, "modules")
    shutil.move(os.path.join(moved, "share/tirefe/lua"), modules)
    host = os.path.join(folder, "consumer", "press_tire")
    missing = run([host], env=host_env(moved), check=False)
    assert missing.returncode == 1, missing
    assert "cannot find tirefe's Lua modules" in missing.stderr and "TIREFE_LUA_PATH" in missing.stderr, missing.stderr
    env = dict(host_env(moved), TIREFE_LUA_PATH=modules)
    check_same(run([host], env=env).stdout, reference())


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_install_")
