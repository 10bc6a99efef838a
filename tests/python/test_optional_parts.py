# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The tests that need an optional Debian package (tools/setup/debian-packages.txt) are left out
when configuring finds no tool for them, with a message, instead of failing the build or the
suite: without pytest every pytest file, without Sphinx the HTML test, without venv the venv
test, with TAPMC_BUILD_GTESTS=OFF (tools/setup/build.sh's setting without libgtest-dev) the
GoogleTest suites, and without clang's fuzzer runtime (libclang-rt-dev) the fuzz test. A Python
without a module is /usr/bin/python3 with a folder first on PYTHONPATH whose stand-in modules
fail to import; clang without its runtime is a script that fails to link as clang does. When
every optional package is installed (CI), the build under test has every one of those tests.
Configure steps only, in build directories of their own: seconds each."""

import os
import re
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))
PYTHON = "/usr/bin/python3"
CLANG_WITHOUT_RUNTIME = """#!/bin/sh
echo "/usr/bin/ld: cannot find libclang_rt.fuzzer-x86_64.a: No such file or directory" >&2
echo "clang: error: linker command failed with exit code 1 (use -v to see invocation)" >&2
exit 1
"""


def cache_value(name):
    m = re.search(rf"^{name}:\w+=(.*)$", (BUILD / "CMakeCache.txt").read_text(), re.M)
    return m.group(1) if m else None


def python_without(tmp_path, *modules):
    """A TAPMC_PYTHON that cannot import the modules given."""
    blocked = tmp_path / "blocked"
    blocked.mkdir()
    for module in modules:
        (blocked / f"{module}.py").write_text(f"raise ImportError('{module}: blocked by the "
                                              "test')\n")
    wrapper = tmp_path / "python3"
    wrapper.write_text(f'#!/bin/sh\nPYTHONPATH="{blocked}${{PYTHONPATH:+:$PYTHONPATH}}" '
                       f'exec {PYTHON} "$@"\n')
    wrapper.chmod(0o755)
    return wrapper


def configure(tmp_path, *options):
    """(configure output, names of the tests registered) of a build directory of its own."""
    build = tmp_path / "build"
    env = {k: v for k, v in os.environ.items() if not k.startswith("TAPMC_")}
    out = subprocess.run(
        ["cmake", "-S", str(SOURCE), "-B", str(build), "-DTAPMC_BUILD_BENCH=OFF",
         "-DLAMMPS_DIR=" + cache_value("LAMMPS_DIR"),
         "-DTAPMC_LAMMPS_HEADERS_DIR=" + cache_value("TAPMC_LAMMPS_HEADERS_DIR"), *options],
        env=env, capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
    assert out.returncode == 0, out.stdout + out.stderr
    return " ".join(out.stdout.split()), registered(build)


def registered(build):
    out = subprocess.run(["ctest", "--test-dir", str(build), "-N"], capture_output=True,
                         text=True, timeout=60)
    return set(re.findall(r"Test +#\d+: (\S+)", out.stdout))


def test_without_pytest_the_pytest_files_are_left_out(tmp_path):
    text, tests = configure(tmp_path, "-DTAPMC_PYTHON=%s" % python_without(tmp_path, "pytest"))
    assert "has no pytest (Debian: python3-pytest): the pytest files of the tests are left out" \
        in text, text
    pytest_files = {t for t in tests if re.match(r"(lammps|python|docs|pores)\.test_", t)}
    assert pytest_files == set(), sorted(pytest_files)
    assert "mpi.lammps_tests_np2" in tests   # the GoogleTest suites stay


def test_without_googletest_sphinx_venv_or_the_fuzzer_runtime_their_tests_are_left_out(tmp_path):
    clang = tmp_path / "clang++"
    clang.write_text(CLANG_WITHOUT_RUNTIME)
    clang.chmod(0o755)
    python = python_without(tmp_path, "sphinx", "ensurepip")
    text, tests = configure(tmp_path, "-DTAPMC_BUILD_GTESTS=OFF",
                            "-DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON", f"-DTAPMC_PYTHON={python}",
                            f"-DTAPMC_CLANGXX={clang}")
    assert not {t for t in tests if t.startswith("mpi.")}, tests
    assert "docs.test_sphinx_html" not in tests and "python.test_install_venv" not in tests
    assert "(Debian: python3-sphinx): that test is left out" in text, text
    assert "needs (Debian: python3-venv): that test is left out" in text
    assert "pores.fuzz_dump_reader" not in tests
    assert f"TAPMC: {clang} cannot link -fsanitize=fuzzer,address,undefined (/usr/bin/ld: " \
        "cannot find libclang_rt.fuzzer-x86_64.a: No such file or directory; Debian: " \
        "libclang-rt-dev): the fuzz test pores.fuzz_dump_reader is left out" in text
    # the rest of the pytest files stay
    assert {"docs.test_doc_snippets", "python.test_install", "pores.test_cli"} <= tests


def installed(package):
    out = subprocess.run(["dpkg-query", "-W", "-f=${Status}", package], capture_output=True,
                         text=True)
    return "install ok installed" in out.stdout


def test_with_every_optional_package_every_such_test_is_there():
    """What CI runs (as root, every package installed): nothing is left out."""
    listed = (SOURCE / "tools/setup/debian-packages.txt").read_text()
    optional = re.findall(r"^optional (\S+)", listed, re.M)
    if not all(installed(p) for p in optional):
        pytest.skip("not every optional package is installed: "
                    + " ".join(p for p in optional if not installed(p)))
    tests = registered(BUILD)
    assert {"docs.test_sphinx_html", "python.test_install_venv", "pores.fuzz_dump_reader",
            "mpi.lammps_tests_np2", "python.test_install"} <= tests
    for prefix in ("unit", "lammps", "pores"):   # GoogleTest cases: PREFIX.Suite.Case
        assert any(re.match(prefix + r"\.[A-Z]\w*\.\w+$", t) for t in tests), prefix
