# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Route 1 of doc/install.rst (your own LAMMPS), its configure step on a machine without Debian's
tools: with a PATH that holds only the compilers and binutils, make, CMake and the MPI wrappers
(no apt, apt-get, dpkg or sudo) and an empty HOME (no cache of TAPMC's in ~/.cache), TAPMC configures
against the LAMMPS of the build under test with -DLAMMPS_DIR and -DTAPMC_LAMMPS_HEADERS_DIR,
looks for neither GoogleTest nor CGAL when their parts are off, and writes nothing into HOME.
Without the headers, or with a directory that is not a LAMMPS source tree, it stops with a
message naming TAPMC_LAMMPS_HEADERS_DIR and touches nothing; with the tests or the pore tool on
and GoogleTest or CGAL missing, the message names the option that turns that part off. Only
configure steps: seconds, nothing is compiled but CMake's probes. The end-to-end route (build,
install, run, plugin load) is tests/lammps/test_slow_own_lammps.py."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))
sys.path.insert(0, str(SOURCE / "tests" / "lammps"))
from lammps_builds import toolchain_only_path, user_environment  # noqa: E402

PARTS_OFF = ["-DTAPMC_BUILD_TESTS=OFF", "-DTAPMC_BUILD_PORES=OFF", "-DTAPMC_BUILD_BENCH=OFF"]


def cache_value(build, name):
    m = re.search(rf"^{name}:\w+=(.*)$", (build / "CMakeCache.txt").read_text(), re.M)
    return m.group(1) if m else None


@pytest.fixture(scope="module")
def lammps():
    """(LAMMPS_DIR, TAPMC_LAMMPS_HEADERS_DIR) of the build under test: a LAMMPS CMake package
    and a source tree of the same version (Debian's LAMMPS and the headers in TAPMC's cache for
    the build of tools/setup.sh)."""
    lammps_dir = cache_value(BUILD, "LAMMPS_DIR")
    headers = cache_value(BUILD, "TAPMC_LAMMPS_HEADERS_DIR")
    assert lammps_dir and Path(lammps_dir, "LAMMPSConfig.cmake").is_file(), lammps_dir
    assert headers and Path(headers, "src", "neigh_request.h").is_file(), headers
    return lammps_dir, headers


@pytest.fixture
def user(tmp_path):
    """(environment, empty HOME) of a user with no Debian tools on PATH."""
    home = tmp_path / "home"
    home.mkdir()
    path = toolchain_only_path(str(tmp_path / "bin"))
    return user_environment(home, path), home


def configure(env, build, *options):
    return subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(build), *options], env=env,
                          capture_output=True, text=True, timeout=300,
                          stdin=subprocess.DEVNULL)


def written(home):
    return sorted(str(p) for p in home.rglob("*"))


def test_own_lammps_configures_without_debian_tools_or_home(lammps, user, tmp_path):
    env, home = user
    lammps_dir, headers = lammps
    build = tmp_path / "build"
    out = configure(env, build, "-DLAMMPS_DIR=" + lammps_dir,
                    "-DTAPMC_LAMMPS_HEADERS_DIR=" + headers, *PARTS_OFF)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "fetching" not in out.stdout
    assert written(home) == [], "configuring wrote into HOME: %s" % written(home)
    assert cache_value(build, "LAMMPS_DIR") == lammps_dir
    assert cache_value(build, "TAPMC_LAMMPS_HEADERS_DIR") == headers
    # GoogleTest and CGAL are looked for only when their parts are on
    assert cache_value(build, "GTest_DIR") is None
    assert cache_value(build, "CGAL_DIR") is None
    assert (build / "CMakeFiles" / "lmp_tapmc.dir").is_dir()
    assert (build / "tapmc-paper").is_file()


def test_missing_headers_stop_configure_naming_the_variable(lammps, user, tmp_path):
    """No TAPMC_LAMMPS_HEADERS_DIR and none in the (empty) cache: no fetch is tried without
    Debian's tools, and the message says what to give."""
    env, home = user
    out = configure(env, tmp_path / "build", "-DLAMMPS_DIR=" + lammps[0], *PARTS_OFF)
    assert out.returncode != 0, out.stdout
    message = " ".join(out.stderr.split())
    assert "-DTAPMC_LAMMPS_HEADERS_DIR=<the top directory of the LAMMPS source tree" in message, \
        out.stderr
    assert "fetching" not in out.stdout
    assert written(home) == [], written(home)


def test_a_src_directory_is_refused_and_left_alone(lammps, user, tmp_path):
    """A user's directory is read, never fetched into or deleted: here the src/ directory of a
    tree instead of its top."""
    env, home = user
    tree = tmp_path / "mylammps"
    (tree / "src").mkdir(parents=True)
    (tree / "src" / "neigh_request.h").write_text("// not a real header\n")
    out = configure(env, tmp_path / "build", "-DLAMMPS_DIR=" + lammps[0],
                    "-DTAPMC_LAMMPS_HEADERS_DIR=" + str(tree / "src"), *PARTS_OFF)
    assert out.returncode != 0, out.stdout
    message = " ".join(out.stderr.split())
    assert "TAPMC_LAMMPS_HEADERS_DIR = %s has no src/neigh_request.h" % (tree / "src") in message
    assert "give its parent" in message, out.stderr
    assert sorted(p.name for p in tree.rglob("*")) == ["neigh_request.h", "src"]
    assert written(home) == []


@pytest.mark.parametrize("package, option", [("GTest", "TAPMC_BUILD_TESTS"),
                                             ("CGAL", "TAPMC_BUILD_PORES")])
def test_missing_optional_dependency_names_the_option_that_drops_it(lammps, user, tmp_path,
                                                                    package, option):
    env, _ = user
    parts = {"TAPMC_BUILD_TESTS": "OFF", "TAPMC_BUILD_PORES": "OFF", "TAPMC_BUILD_BENCH": "OFF"}
    parts[option] = "ON"
    out = configure(env, tmp_path / "build", "-DLAMMPS_DIR=" + lammps[0],
                    "-DTAPMC_LAMMPS_HEADERS_DIR=" + lammps[1],
                    "-DCMAKE_DISABLE_FIND_PACKAGE_%s=ON" % package,
                    *("-D%s=%s" % item for item in parts.items()))
    assert out.returncode != 0, out.stdout
    assert "-D%s=OFF" % option in " ".join(out.stderr.split()), out.stderr
