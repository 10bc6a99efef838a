# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Route 1 of doc/install.rst end to end (label "slow"): a LAMMPS of one's own, built from source
with CMake as a shared library and installed, with its source tree beside it. Here that LAMMPS
is one that tools/setup/build-lammps-plugin.sh built into the user's cache (lammps_builds.py;
skipped when it is not built, unless TAPMC_SLOW=1, which builds it). As a user without Debian's
tools would, with an empty HOME and a PATH of compilers, binutils, make, CMake and MPI wrappers,
TAPMC is configured with -DLAMMPS_DIR=<its prefix>/lib/cmake/LAMMPS and
-DTAPMC_LAMMPS_HEADERS_DIR=<its source tree>, and nothing else of this machine's set-up; built
(tapmc, lmp_tapmc); installed with `cmake --install` into a temporary prefix. The installed
lmp_tapmc runs examples/tapping/in.tapping_pbc for 2 taps on that LAMMPS (not Debian's), and
that LAMMPS's own lmp runs the same input after `plugin load <prefix>/lib/libtapmc.so`, with
the same thermo output, digit for digit.

The source tree is the one the LAMMPS was built from when the script kept it
(build-lammps-plugin.sh --keep-build: <install>.work/source), else the copy of its headers
that the script leaves in TAPMC's cache (<cache>/lammps-<version>: src/*.h, src/fmt/ and
src/version.h, all that TAPMC reads of a tree)."""

import os
import re
import shutil
from pathlib import Path

import pytest

from lammps_builds import (LAMMPS_BUILDS, SOURCE_DIR, lammps_prefix, run, toolchain_only_path,
                           user_environment)
from lmprun import thermo_table

TAPS = 2
EXAMPLE = Path("tapping", "in.tapping_pbc")


def lammps_version(prefix):
    """The version of the LAMMPS installed in prefix as 20210929 (LAMMPSConfigVersion.cmake
    says 20210929 up to 2022, 2026.7.4.0 later)."""
    text = Path(prefix, "lib", "cmake", "LAMMPS", "LAMMPSConfigVersion.cmake").read_text()
    version = re.search(r'set\(PACKAGE_VERSION "([0-9.]+)"\)', text).group(1)
    if re.fullmatch(r"[0-9]{8}", version):
        return version
    year, month, day = version.split(".")[:3]
    return "%04d%02d%02d" % (int(year), int(month), int(day))


def source_tree(prefix):
    kept = prefix + ".work/source"
    if os.path.isfile(os.path.join(kept, "src", "neigh_request.h")):
        return kept
    headers = os.path.join(os.path.dirname(prefix), "lammps-" + lammps_version(prefix))
    assert os.path.isfile(os.path.join(headers, "src", "neigh_request.h")), \
        f"neither the source tree {kept} nor the headers {headers} of the LAMMPS in {prefix}"
    return headers


@pytest.fixture(scope="module", params=sorted(LAMMPS_BUILDS))
def route1(request, tmp_path_factory):
    """Configure, build and install TAPMC against the LAMMPS `request.param` as route 1 says."""
    lammps = lammps_prefix(request.param)
    tree = source_tree(lammps)
    top = tmp_path_factory.mktemp("own-lammps-" + request.param)
    home = top / "home"
    home.mkdir()
    env = user_environment(home, toolchain_only_path(str(top / "bin")))
    build, prefix = top / "build", top / "prefix"
    lammps_dir = os.path.join(lammps, "lib", "cmake", "LAMMPS")
    rc, out = run(["cmake", "-S", SOURCE_DIR, "-B", str(build), "-DLAMMPS_DIR=" + lammps_dir,
                   "-DTAPMC_LAMMPS_HEADERS_DIR=" + tree, "-DTAPMC_BUILD_TESTS=OFF",
                   "-DTAPMC_BUILD_PORES=OFF", "-DTAPMC_BUILD_BENCH=OFF"], cwd=str(top), env=env)
    assert rc == 0, out
    assert "fetching" not in out, out
    rc, out = run(["cmake", "--build", str(build), "--target", "tapmc", "lmp_tapmc", "-j", "2"],
                  cwd=str(top), env=env, timeout=3 * 3600)
    assert rc == 0, out
    rc, out = run(["cmake", "--install", str(build), "--prefix", str(prefix)], cwd=str(top),
                  env=env)
    assert rc == 0, out
    return {"lammps": lammps, "lammps_dir": lammps_dir, "tree": tree, "build": build,
            "prefix": prefix, "home": home,
            # running needs no toolchain: the user's PATH, still an empty HOME
            "run_env": user_environment(home, os.environ["PATH"])}


def measurements(log_text):
    """Thermo rows without the timing column (cpuremain: CPULeft differs run to run)."""
    names, table = thermo_table(log_text)
    keep = [k for k, name in enumerate(names) if name not in ("CPU", "CPULeft")]
    return [names[k] for k in keep], table[:, keep].tolist()


def linked_lammps(binary, env):
    rc, out = run(["ldd", str(binary)], cwd="/", env=env)
    assert rc == 0, out
    return [line.split("=>")[1].split("(")[0].strip() for line in out.splitlines()
            if "liblammps" in line and "=>" in line]


def cache_value(build, name):
    m = re.search(rf"^{name}:\w+=(.*)$", (build / "CMakeCache.txt").read_text(), re.M)
    return m.group(1) if m else None


def test_configured_built_and_installed_against_the_given_lammps_only(route1):
    assert cache_value(route1["build"], "LAMMPS_DIR") == route1["lammps_dir"]
    assert cache_value(route1["build"], "TAPMC_LAMMPS_HEADERS_DIR") == route1["tree"]
    assert list(route1["home"].rglob("*")) == [], "wrote into HOME"
    own = os.path.join(route1["lammps"], "lib")
    for binary in (route1["prefix"] / "bin" / "lmp_tapmc", route1["prefix"] / "lib" / "libtapmc.so"):
        libraries = linked_lammps(binary, route1["run_env"])
        assert libraries and all(os.path.realpath(lib).startswith(own) for lib in libraries), \
            (binary, libraries)


@pytest.fixture(scope="module")
def lmp_tapmc_output(route1, tmp_path_factory):
    """The installed example under the installed lmp_tapmc, TAPS taps."""
    workdir = tmp_path_factory.mktemp("lmp_tapmc")
    shutil.copy(route1["prefix"] / "share" / "tapmc" / "examples" / EXAMPLE, workdir)
    rc, out = run([str(route1["prefix"] / "bin" / "lmp_tapmc"), "-in", EXAMPLE.name,
                   "-var", "taps", str(TAPS), "-log", "log.lammps", "-nocite"],
                  cwd=str(workdir), env=route1["run_env"])
    assert rc == 0, out
    return out


def test_installed_lmp_tapmc_runs_the_example(lmp_tapmc_output):
    names, rows = measurements(lmp_tapmc_output)
    assert names[:4] == ["Step", "c_phi[1]", "c_phi[2]", "c_phi[3]"], names
    assert rows[-1][0] == TAPS
    assert 0.5 < rows[-1][1] < 0.65, rows


def test_own_lmp_runs_the_example_with_plugin_load(route1, lmp_tapmc_output, tmp_path):
    library = route1["prefix"] / "lib" / "libtapmc.so"
    shutil.copy(route1["prefix"] / "share" / "tapmc" / "examples" / EXAMPLE, tmp_path)
    (tmp_path / "in.plugin").write_text(f"plugin load {library}\nplugin list\n"
                                        f"include {EXAMPLE.name}\n")
    rc, out = run([os.path.join(route1["lammps"], "bin", "lmp"), "-in", "in.plugin",
                   "-var", "taps", str(TAPS), "-log", "log.lammps", "-nocite"],
                  cwd=str(tmp_path), env=route1["run_env"])
    assert rc == 0, out
    for style in ("fix style plugin tapdilate", "fix style plugin mc/settle",
                  "compute style plugin stereo/profile", "command style plugin create_packing"):
        assert style in out, (style, out)
    # the same library on the same LAMMPS: the same trajectory as lmp_tapmc's
    assert measurements(out) == measurements(lmp_tapmc_output)
