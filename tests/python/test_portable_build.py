# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Portable by default: a fresh configuration has TAPMC_NATIVE OFF and compiles nothing with
-march=native (binaries built on one CPU run on another); -DTAPMC_NATIVE=ON adds it. The build
under test compiles with -march=native exactly when its cache says TAPMC_NATIVE ON (a build
directory configured before the default changed keeps ON). Configuring writes nothing into the
user's home (no tapmc.pth in the user site-packages)."""

import os
import re
import subprocess
from pathlib import Path

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))


def cache_value(build, name):
    m = re.search(rf"^{name}:\w+=(.*)$", (build / "CMakeCache.txt").read_text(), re.M)
    return m.group(1) if m else None


def compile_flags(build):
    """{flags.make file: its text} of every target of the build."""
    return {p: p.read_text() for p in build.rglob("CMakeFiles/*.dir/flags.make")}


def test_fresh_configuration_is_portable_and_writes_nothing_home(tmp_path):
    build = tmp_path / "build"
    home = tmp_path / "home"
    home.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("XDG_CACHE_HOME", "PYTHONUSERBASE")}
    env["HOME"] = str(home)
    configure = ["cmake", "-S", str(SOURCE), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                 "-DTAPMC_BUILD_TESTS=OFF", "-DTAPMC_BUILD_PORES=OFF", "-DTAPMC_BUILD_BENCH=OFF"]
    headers = cache_value(BUILD, "TAPMC_LAMMPS_HEADERS_DIR")
    if headers:  # the headers the build under test uses (HOME is empty here)
        configure.append("-DTAPMC_LAMMPS_HEADERS_DIR=" + headers)
    out = subprocess.run(configure, env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert cache_value(build, "TAPMC_NATIVE") == "OFF"
    flags = compile_flags(build)
    assert any("lmp_tapmc.dir" in str(p) for p in flags), sorted(map(str, flags))
    native = [str(p) for p, text in flags.items() if "-march=native" in text]
    assert not native, native
    assert list(home.rglob("*")) == [], "configuring wrote into HOME: %s" % list(home.rglob("*"))
    assert (build / "tapmc-paper").is_file()

    out = subprocess.run(["cmake", "-DTAPMC_NATIVE=ON", str(build)], env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    flags = compile_flags(build)
    assert all("-march=native" in flags[p] for p in flags
               if p.parent.name in ("tapmc.dir", "lmp_tapmc.dir", "tapmc_kernels.dir")), flags


def test_build_under_test_uses_march_native_only_when_asked():
    native = cache_value(BUILD, "TAPMC_NATIVE")
    assert native in ("ON", "OFF"), native
    flags = compile_flags(BUILD)
    assert flags
    with_native = sorted(str(p) for p, text in flags.items() if "-march=native" in text)
    if native == "OFF":
        assert not with_native, with_native
    else:
        assert with_native, "TAPMC_NATIVE=ON but no target compiles with -march=native"
