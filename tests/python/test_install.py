# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""`cmake --install` of the build under test into a temporary prefix (no root): the installed
files (doc/install.rst lists them), the programs run from the prefix and find libtapmc.so through
their RUNPATH (also after the prefix moved), the installed tapmc-paper imports the installed
package and not the source tree nor a folder tapmc of the current directory, an absolute
TAPMC_INSTALL_PYTHONDIR, a downstream CMake project finds TAPMC::tapmc, and every program prints
the one version of tools/python/tapmc/__init__.py. An install again removes the modules of the
earlier one; the target uninstall removes the last install (BUILD/install_manifest.txt, which
docs.test_doc_snippets writes too: the two hold one ctest resource lock)."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))
PYTHONDIR = Path("lib/python3/dist-packages")
PORES_BUILT = (BUILD / "tools/pores/tapmc-pores").exists()


def source_version():
    text = (SOURCE / "tools/python/tapmc/__init__.py").read_text()
    return re.search(r'^__version__ = "([0-9.]+)"$', text, re.M).group(1)


def clean_env(**extra):
    """The environment of a user of the prefix: nothing pointing at the build or the source
    tree except PYTHONPATH, which ctest points at the source tree (the installed programs must
    not use it in place of their own package)."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("TAPMC_") and k not in ("LD_LIBRARY_PATH",)}
    env["PYTHONPATH"] = str(SOURCE / "tools/python")
    env.update(extra)
    return env


def run(cmd, **kw):
    kw.setdefault("env", clean_env())
    kw.setdefault("timeout", 120)
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True,
                          stdin=subprocess.DEVNULL, **kw)


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    prefix = tmp_path_factory.mktemp("prefix")
    out = run(["cmake", "--install", BUILD, "--prefix", prefix])
    assert out.returncode == 0, out.stdout + out.stderr
    return prefix


def test_installed_files(prefix):
    expected = ["bin/lmp_tapmc", "bin/tapmc-paper", "lib/libtapmc.so",
                "lib/cmake/TAPMC/TAPMCConfig.cmake", "lib/cmake/TAPMC/TAPMCConfigVersion.cmake",
                "include/tapmc/register_styles.h", PYTHONDIR / "tapmc/__init__.py",
                PYTHONDIR / "tapmc/paper/__main__.py",
                "share/tapmc/examples/tapping/in.tapping_pbc",
                "share/tapmc/examples/paper/in.constant_eps",
                "share/doc/tapmc/README.md", "share/doc/tapmc/install.rst",
                "share/doc/tapmc/tapmc-paper.rst"]
    if PORES_BUILT:
        expected.append("bin/tapmc-pores")
    missing = [str(p) for p in expected if not (prefix / p).is_file()]
    assert not missing, missing
    for program in ("lmp_tapmc", "tapmc-paper") + (("tapmc-pores",) if PORES_BUILT else ()):
        assert os.access(prefix / "bin" / program, os.X_OK), program
    # the whole Python package, its data files (claims.toml, ...) included
    package = SOURCE / "tools/python/tapmc"
    wanted = {p.relative_to(package) for p in package.rglob("*")
              if p.is_file() and "__pycache__" not in p.parts}
    installed = {p.relative_to(prefix / PYTHONDIR / "tapmc")
                 for p in (prefix / PYTHONDIR / "tapmc").rglob("*") if p.is_file()}
    assert wanted - installed == set(), sorted(wanted - installed)
    # no outputs of local runs and no campaign data
    assert not list((prefix / "share/tapmc/examples").rglob("log.lammps"))
    assert not (prefix / "share/doc/tapmc/validation/data").exists()


def runpath(binary):
    out = run(["readelf", "-d", binary])
    assert out.returncode == 0, out.stderr
    return re.findall(r"\((?:RUNPATH|RPATH)\)\s+Library r(?:un)?path: \[(.*)\]", out.stdout)


def test_programs_find_libtapmc_through_their_runpath(prefix):
    paths = runpath(prefix / "bin/lmp_tapmc")
    assert paths and "$ORIGIN/../lib" in paths[0].split(":"), paths
    out = run(["ldd", prefix / "bin/lmp_tapmc"])
    assert out.returncode == 0, out.stderr
    line = next(l for l in out.stdout.splitlines() if "libtapmc.so" in l)
    assert f"=> {prefix}/bin/../lib/libtapmc.so" in line or f"=> {prefix}/lib/libtapmc.so" in line, \
        line


def test_installed_lmp_tapmc_runs_two_taps_of_the_installed_example(prefix, tmp_path):
    shutil.copy(prefix / "share/tapmc/examples/tapping/in.tapping_pbc", tmp_path)
    out = run([prefix / "bin/lmp_tapmc", "-in", "in.tapping_pbc", "-var", "taps", "2",
               "-log", "none", "-nocite"], cwd=tmp_path, timeout=300)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr
    assert "Loop time" in out.stdout, out.stdout[-3000:]


def test_installed_programs_print_the_one_version(prefix):
    version = source_version()
    out = run([prefix / "bin/tapmc-paper", "--version"])
    assert out.returncode == 0 and out.stdout == f"tapmc-paper {version}\n", out
    if PORES_BUILT:
        out = run([prefix / "bin/tapmc-pores", "--version"])
        assert out.returncode == 0 and out.stdout == f"tapmc-pores {version}\n", out


def test_one_version_everywhere():
    """tapmc.__version__ is the project's VERSION (CMake reads it) and what the build-tree
    programs print."""
    version = source_version()
    cache = (BUILD / "CMakeCache.txt").read_text()
    assert f"CMAKE_PROJECT_VERSION:STATIC={version}\n" in cache
    out = run([BUILD / "tapmc-paper", "--version"])
    assert out.stdout == f"tapmc-paper {version}\n", out
    if PORES_BUILT:
        out = run([BUILD / "tools/pores/tapmc-pores", "--version"])
        assert out.stdout == f"tapmc-pores {version}\n", out


def launcher_settings(launcher):
    """The variables the installed tapmc-paper sets before it starts Python (sh -x)."""
    out = run(["sh", "-x", launcher, "--version"], env={"PATH": os.environ["PATH"]})
    assert out.returncode == 0, out.stderr
    settings = {}
    for line in out.stderr.splitlines():
        m = re.match(r"^\++ (?:export )?([A-Z_]+)=(.*)$", line)
        if m:
            settings[m.group(1)] = m.group(2).strip("'\"")
    return settings


def test_moved_prefix_uses_its_own_package_programs_and_examples(prefix, tmp_path):
    """A copy of the prefix elsewhere: its tapmc-paper imports the copy's package (here marked
    by its version) even with the source tree on PYTHONPATH, and points at the copy's programs
    and examples; its lmp_tapmc loads the copy's libtapmc.so."""
    moved = tmp_path / "moved"
    shutil.copytree(prefix, moved, symlinks=True)
    init = moved / PYTHONDIR / "tapmc/__init__.py"
    init.write_text(init.read_text().replace(f'__version__ = "{source_version()}"',
                                             '__version__ = "0.0.0+moved"'))
    out = run([moved / "bin/tapmc-paper", "--version"])
    assert out.stdout == "tapmc-paper 0.0.0+moved\n", out
    settings = launcher_settings(moved / "bin/tapmc-paper")
    assert settings.get("PYTHONPATH") == str(moved / PYTHONDIR), settings
    assert settings.get("TAPMC_LMP") == str(moved / "bin/lmp_tapmc"), settings
    assert settings.get("TAPMC_PORES") == str(moved / "bin/tapmc-pores"), settings
    assert settings.get("TAPMC_DATA_DIR") == str(moved / "share/tapmc"), settings
    # the package reads the paper's inputs from TAPMC_DATA_DIR
    code = ("from tapmc.paper import _runs; import os, tapmc; print(tapmc.__file__); "
            "print(_runs._input(_runs.CONSTANT_EPS))")
    out = run([sys.executable, "-c", code],
              env=clean_env(PYTHONPATH=str(moved / PYTHONDIR),
                            TAPMC_DATA_DIR=str(moved / "share/tapmc")))
    assert out.returncode == 0, out.stderr
    module, example = out.stdout.split()
    assert module.startswith(str(moved)) and Path(example).is_file(), out.stdout
    out = run(["ldd", moved / "bin/lmp_tapmc"])
    line = next(l for l in out.stdout.splitlines() if "libtapmc.so" in l)
    assert str(moved) in line, line
    (tmp_path / "in.tiny").write_text(TINY)
    out = run([moved / "bin/lmp_tapmc", "-in", "in.tiny", "-log", "none", "-nocite"],
              cwd=tmp_path)
    assert out.returncode == 0 and "Loop time" in out.stdout, out.stdout[-2000:] + out.stderr


# TAPMC styles (create_packing, fix tapdilate, fix mc/settle), one tap of 20 spheres
TINY = """units           lj
atom_style      sphere
boundary        p p fm
region          box block 0 4 0 4 0 20
create_box      1 box
create_packing  20 1 0.5 4928 floor 0.0
fix             tap all tapdilate 0.01 floor 0.0
fix             settle all mc/settle 4928 floor 0.0
run             1
"""


DOWNSTREAM = """cmake_minimum_required(VERSION 3.18)
project(downstream CXX)
find_package(TAPMC {major_minor} REQUIRED)
message(STATUS "TAPMC_VERSION=${{TAPMC_VERSION}}")
add_executable(downstream main.cpp)
target_link_libraries(downstream PRIVATE TAPMC::tapmc)
"""
MAIN = """#include "register_styles.h"
#include <cstdio>
int main() {
  int (*volatile reg)(void *) = &tapmc_register;  // resolved by the dynamic linker at start
  std::printf("tapmc_register %s\\n", reg ? "found" : "missing");
}
"""


def test_downstream_cmake_project_links_TAPMC_tapmc(prefix, tmp_path):
    version = source_version()
    src = tmp_path / "src"
    src.mkdir()
    (src / "CMakeLists.txt").write_text(DOWNSTREAM.format(
        major_minor=".".join(version.split(".")[:2])))
    (src / "main.cpp").write_text(MAIN)
    out = run(["cmake", "-S", src, "-B", tmp_path / "b", f"-DCMAKE_PREFIX_PATH={prefix}"])
    assert out.returncode == 0, out.stdout + out.stderr
    assert f"TAPMC_VERSION={version}" in out.stdout
    out = run(["cmake", "--build", tmp_path / "b"], timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    out = run([tmp_path / "b/downstream"])
    assert out.returncode == 0 and out.stdout == "tapmc_register found\n", out


def test_installed_tapmc_paper_ignores_a_tapmc_folder_in_the_current_directory(prefix, tmp_path):
    """`python -m` puts the current directory first on sys.path: run from a folder holding a
    package tapmc (a checkout's tools/python), the installed tapmc-paper must still run the
    installed package (PYTHONSAFEPATH)."""
    shadow = tmp_path / "tapmc" / "paper"
    shadow.mkdir(parents=True)
    (tmp_path / "tapmc" / "__init__.py").write_text("")
    (shadow / "__init__.py").write_text("")
    (shadow / "__main__.py").write_text("print('the shadow package of the current directory')\n")
    out = run([prefix / "bin/tapmc-paper", "--version"], cwd=tmp_path,
              env=clean_env(PYTHONPATH=""))
    assert out.returncode == 0 and out.stdout == f"tapmc-paper {source_version()}\n", out


def test_a_python_dir_given_as_an_absolute_path_is_used_as_it_is(tmp_path):
    """-DTAPMC_INSTALL_PYTHONDIR=/abs/path: the package goes there and the installed
    tapmc-paper takes it from there (not from PREFIX//abs/path). Configured in a build directory
    of its own without the compiled parts; the install rules of tools/python alone run."""
    cache = (BUILD / "CMakeCache.txt").read_text()
    given = {name: re.search(rf"^{name}:\w+=(.*)$", cache, re.M).group(1)
             for name in ("LAMMPS_DIR", "TAPMC_LAMMPS_HEADERS_DIR")}
    pythondir = tmp_path / "site" / "packages"
    build = tmp_path / "build"
    out = run(["cmake", "-S", SOURCE, "-B", build, "-DTAPMC_BUILD_TESTS=OFF",
               "-DTAPMC_BUILD_PORES=OFF", "-DTAPMC_BUILD_BENCH=OFF",
               *(f"-D{name}={value}" for name, value in given.items()),
               f"-DTAPMC_INSTALL_PYTHONDIR={pythondir}"], timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    prefix = tmp_path / "prefix"
    out = run(["cmake", f"-DCMAKE_INSTALL_PREFIX={prefix}", "-P",
               build / "tools/python/cmake_install.cmake"])
    assert out.returncode == 0, out.stdout + out.stderr
    assert (pythondir / "tapmc/__init__.py").is_file()
    assert not (prefix / str(pythondir).lstrip("/")).exists()
    assert launcher_settings(prefix / "bin/tapmc-paper").get("PYTHONPATH") == str(pythondir)
    init = pythondir / "tapmc/__init__.py"
    init.write_text(init.read_text().replace(f'__version__ = "{source_version()}"',
                                             '__version__ = "0.0.0+absolute"'))
    out = run([prefix / "bin/tapmc-paper", "--version"], env=clean_env(PYTHONPATH=""))
    assert out.stdout == "tapmc-paper 0.0.0+absolute\n", out


def install(prefix):
    out = run(["cmake", "--install", BUILD, "--prefix", prefix])
    assert out.returncode == 0, out.stdout + out.stderr
    return out.stdout


def test_an_install_again_removes_modules_of_the_earlier_one(tmp_path):
    """A module of an earlier install that the package no longer has must not stay importable:
    the second install removes the package folder first (and only that folder)."""
    prefix = tmp_path / "prefix"
    install(prefix)
    package = prefix / PYTHONDIR / "tapmc"
    (package / "removed_upstream.py").write_text("GONE = False\n")
    (package / "__pycache__").mkdir(exist_ok=True)
    (prefix / PYTHONDIR / "beside.py").write_text("")   # not ours: stays
    printed = install(prefix)
    assert f"Removing the earlier install of the package: {package}" in printed
    assert not (package / "removed_upstream.py").exists()
    assert (package / "paper/__main__.py").is_file() and (prefix / PYTHONDIR / "beside.py").exists()


def test_uninstall_removes_the_last_install_and_nothing_else(tmp_path):
    prefix = tmp_path / "prefix"
    install(prefix)
    manifest = (BUILD / "install_manifest.txt").read_text().split()
    assert manifest and all(path.startswith(f"{prefix}/") for path in manifest)
    (prefix / PYTHONDIR / "tapmc/__pycache__").mkdir(exist_ok=True)
    (prefix / PYTHONDIR / "tapmc/__pycache__/cli.cpython-311.pyc").write_text("")
    (prefix / "bin/mine").write_text("a file of the user's\n")
    (prefix / "share/tapmc/notes.txt").write_text("a file of the user's in TAPMC's folder\n")
    out = run(["cmake", "--build", BUILD, "--target", "uninstall"])
    assert out.returncode == 0, out.stdout + out.stderr
    assert f"Removing: {prefix}/bin/lmp_tapmc" in out.stdout
    assert f"Removing the Python package folder: {prefix / PYTHONDIR / 'tapmc'}" in out.stdout
    left = sorted(str(p.relative_to(prefix)) for p in prefix.rglob("*") if not p.is_dir())
    assert left == ["bin/mine", "share/tapmc/notes.txt"], left
    for folder in ("share/doc/tapmc", "include/tapmc", "lib/cmake/TAPMC", PYTHONDIR / "tapmc",
                   "share/tapmc/examples"):
        assert not (prefix / folder).exists(), folder


def test_uninstall_without_a_manifest_removes_nothing_and_says_why(tmp_path):
    missing = tmp_path / "install_manifest.txt"
    out = run(["cmake", f"-DMANIFEST={missing}", "-P", BUILD / "TAPMCUninstall.cmake"])
    assert out.returncode != 0
    text = " ".join(out.stderr.split())
    assert f"there is no {missing}, the list of the files that `cmake --install`" in text, text
    assert "so nothing is known to remove" in text
