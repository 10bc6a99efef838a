# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The LAMMPS builds the slow tests run TAPMC against, besides Debian's binary LAMMPS: each is
# built by tools/setup/build-lammps-plugin.sh from a Debian source package into the user's cache
# (PLUGIN, exceptions, MPI, shared library), and TAPMC is compiled against it in a directory of
# the test build. A test skips (with the command to run) when the LAMMPS is not built, unless
# TAPMC_SLOW=1, which builds it.
import os
import subprocess

import pytest

SOURCE_DIR = os.path.abspath(os.environ.get("TAPMC_SOURCE_DIR", "../.."))
BUILD_DIR = os.path.abspath(os.environ.get("TAPMC_BUILD_DIR", "../../build"))
BUILD_SCRIPT = os.path.join(SOURCE_DIR, "tools", "setup", "build-lammps-plugin.sh")

# name -> (environment of build-lammps-plugin.sh, TAPMC build directory under BUILD_DIR, whether
#          that TAPMC build has the test suite, what building that LAMMPS takes on two busy cores)
LAMMPS_BUILDS = {
    # the version of Debian's liblammps0 (29 Sep 2021 on Debian 12; Debian source 20220106...)
    "debian": ({}, "lammps-plugin", False, "about 15 minutes"),
    # the current release, from Debian unstable's original tarball; the LAMMPS-level tests run
    # against it (test_slow_lammps_current.py)
    "2026": ({"TAPMC_LAMMPS_SRC_VERSION": "20260704+dfsg-2",
              "TAPMC_LAMMPS_SRC_SUITE": "unstable"}, "lammps-2026", True, "about 40 minutes"),
}


def run(cmd, cwd, env=None, timeout=1800):
    proc = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL)
    return proc.returncode, proc.stdout


def cached_build_setting(name, default):
    try:
        with open(os.path.join(BUILD_DIR, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith(name + ":"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return default


def lammps_prefix(name):
    """Install prefix of the LAMMPS build `name` (built first when TAPMC_SLOW=1; the test is
    skipped when it is missing otherwise)."""
    settings, _, _, duration = LAMMPS_BUILDS[name]
    env = dict(os.environ, **settings)
    rc, out = run(["bash", BUILD_SCRIPT, "--print-prefix"], cwd=SOURCE_DIR, env=env)
    assert rc == 0, out
    prefix = out.strip()
    if os.environ.get("TAPMC_SLOW") == "1":
        rc, out = run(["bash", BUILD_SCRIPT], cwd=SOURCE_DIR, env=env, timeout=6 * 3600)
        assert rc == 0, out
    elif not os.path.exists(os.path.join(prefix, ".tapmc-lammps-plugin")):
        assignments = " ".join(f"{k}={v}" for k, v in settings.items())
        pytest.skip(f"no LAMMPS ({name}) with PLUGIN and exceptions in {prefix}: build it with "
                    f"{assignments + ' ' if assignments else ''}"
                    f"tools/setup/build-lammps-plugin.sh ({duration} on two busy cores), or run "
                    "with TAPMC_SLOW=1 to let this test build it")
    return prefix


def tapmc_against(name, prefix, targets):
    """Configure TAPMC against the LAMMPS in `prefix` (its headers, its liblammps, exceptions) in
    BUILD_DIR/<dir>, with the compiler settings of the main build so that the kernels are the
    same machine code, and build `targets`. Returns the build directory."""
    _, directory, tests, _ = LAMMPS_BUILDS[name]
    build = os.path.join(BUILD_DIR, directory)
    configure = ["cmake", "-S", SOURCE_DIR, "-B", build,
                 "-DLAMMPS_DIR=" + os.path.join(prefix, "lib", "cmake", "LAMMPS"),
                 "-DCMAKE_BUILD_TYPE=" + cached_build_setting("CMAKE_BUILD_TYPE", "Release"),
                 "-DTAPMC_NATIVE=" + cached_build_setting("TAPMC_NATIVE", "OFF"),
                 "-DTAPMC_BUILD_TESTS=" + ("ON" if tests else "OFF"),
                 "-DTAPMC_BUILD_PORES=OFF", "-DTAPMC_BUILD_BENCH=OFF"]
    rc, out = run(configure, cwd=SOURCE_DIR)
    assert rc == 0, out
    rc, out = run(["cmake", "--build", build, "--target"] + targets + ["-j", "2"],
                  cwd=SOURCE_DIR, timeout=3 * 3600)
    assert rc == 0, out
    return build
