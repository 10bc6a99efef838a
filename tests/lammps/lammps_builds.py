# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The LAMMPS builds the slow tests run TAPMC against, besides Debian's binary LAMMPS: each is
# built by tools/setup/build-lammps-plugin.sh from a Debian source package into the user's cache
# (PLUGIN, exceptions, MPI, shared library), and TAPMC is compiled against it in a directory of
# the test build. A test skips (with the command to run) when the LAMMPS is not built, unless
# TAPMC_SLOW=1, which builds it. Also the environment of a user of route 1 of doc/install.rst
# (your own LAMMPS): a PATH without Debian's tools and an empty HOME.
import os
import shutil
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


# What configuring and building TAPMC runs by name (found on PATH): CMake, the compilers, make,
# the binutils (the assembler and linker the compiler driver calls; ar and ranlib, which CMake
# looks for beside the compiler and on PATH only) and the MPI wrappers FindMPI asks. No apt, dpkg
# or sudo: route 1 of doc/install.rst must work without Debian's tools.
TOOLCHAIN = ("cmake", "cc", "c++", "gcc", "g++", "make", "gmake", "as", "ld", "ar", "ranlib",
             "nm", "strip", "objdump", "objcopy", "readelf", "addr2line", "gcc-ar", "gcc-ranlib",
             "gcc-nm", "mpicxx", "mpicc", "mpiexec")
TOOLCHAIN_REQUIRED = ("cmake", "cc", "c++", "make", "as", "ld", "ar", "ranlib")
DEBIAN_TOOLS = ("apt", "apt-get", "apt-cache", "dpkg", "dpkg-query", "sudo")


def toolchain_only_path(directory):
    """A directory holding symbolic links to the TOOLCHAIN programs found on PATH, and nothing
    else: a PATH of a machine without Debian's package tools. Returns the directory."""
    os.makedirs(directory, exist_ok=True)
    for tool in TOOLCHAIN:
        found = shutil.which(tool)
        if found:
            os.symlink(found, os.path.join(directory, tool))
        elif tool in TOOLCHAIN_REQUIRED:
            pytest.fail(f"'{tool}' is not on PATH: TAPMC cannot be configured without it")
    assert not set(os.listdir(directory)) & set(DEBIAN_TOOLS)
    return directory


def user_environment(home, path):
    """The environment of a user of route 1: HOME an empty directory (no cache of TAPMC or CMake
    in it), PATH as given, nothing of the test build (no TAPMC_*, PYTHONPATH, LD_LIBRARY_PATH) and
    no XDG_CACHE_HOME or CMake hints."""
    drop = ("XDG_CACHE_HOME", "PYTHONPATH", "LD_LIBRARY_PATH", "CMAKE_PREFIX_PATH", "LAMMPS_DIR",
            "CC", "CXX", "CMAKE_GENERATOR")
    env = {k: v for k, v in os.environ.items() if not k.startswith("TAPMC_") and k not in drop}
    env.update(HOME=str(home), PATH=str(path))
    return env


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
