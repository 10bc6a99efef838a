# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The setup scripts of the quick start for a user who is not root (tools/setup/install-deps.sh,
tools/setup/build.sh, tools/setup/fetch-lammps-headers.sh): the Debian packages are required or
optional (tools/setup/debian-packages.txt); as root, or with a sudo that works, every missing
one is installed; without either, missing optional ones are named with what is left out and the
build goes on without those parts, missing required ones stop the script with the apt-get line
for an administrator, and a sudo that refuses is followed by TAPMC's own line. Without network,
the fetch of the LAMMPS headers says that the archive is out of reach and how to go on offline.

Debian's tools are stood in for by small scripts on PATH (dpkg-query reporting the packages of
FAKE_MISSING missing, id, sudo, apt-get and cmake recording their arguments), so nothing is
installed; one case runs as the user nobody for real (as root through setpriv). No network:
http_proxy points at a closed port."""

import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SETUP = SOURCE / "tools" / "setup"
NO_NETWORK = "http://127.0.0.1:9"   # the discard port: nothing listens there, connect fails at once

FAKES = {
    # installed unless named in FAKE_MISSING; the script asks `dpkg-query -W -f=... PACKAGE`
    "dpkg-query": """for last; do :; done
case " $FAKE_MISSING " in *" $last "*) exit 1 ;; esac
printf 'install ok installed'""",
    "id": 'echo "$FAKE_UID"',
    # FAKE_SUDO=refuse: the refusal of a user not in sudoers; else run the command
    "sudo": """echo "sudo $*" >> "$FAKE_LOG"
if [ "$FAKE_SUDO" = refuse ]; then
  echo "Sorry, user $USER is not allowed to execute 'apt-get update -qq' as root." >&2
  exit 1
fi
exec "$@" """,
    "apt-get": 'echo "apt-get $*" >> "$FAKE_LOG"',
    "cmake": 'echo "cmake $*" >> "$FAKE_LOG"',
}
# What the scripts call besides the stand-ins.
TOOLS = ("bash", "env", "dirname", "nproc")


def packages():
    """(kind, package, reason) of every line of debian-packages.txt."""
    rows = []
    for line in (SETUP / "debian-packages.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            kind, package, reason = line.split(maxsplit=2)
            rows.append((kind, package, reason))
    return rows


def package_list(kind):
    return [p for k, p, _ in packages() if k == kind]


@pytest.fixture
def fake(tmp_path):
    """run(script, missing=(), uid=1000, sudo=None|'refuse'|'works') -> (process, log lines)."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in TOOLS:
        os.symlink(shutil.which(tool), bin_dir / tool)
    log = tmp_path / "log"

    def run(script, missing=(), uid=1000, sudo=None):
        for name, body in FAKES.items():
            path = bin_dir / name
            if name == "sudo" and sudo is None:
                path.unlink(missing_ok=True)
                continue
            path.write_text("#!/bin/sh\n" + body + "\n")
            path.chmod(0o755)
        log.write_text("")
        env = {"PATH": str(bin_dir), "HOME": str(tmp_path), "USER": "tapqa",
               "FAKE_MISSING": " ".join(missing), "FAKE_UID": str(uid),
               "FAKE_SUDO": sudo or "", "FAKE_LOG": str(log)}
        out = subprocess.run([str(SETUP / script)], env=env, capture_output=True, text=True,
                             timeout=60, stdin=subprocess.DEVNULL)
        return out, log.read_text().splitlines()

    return run


def tapmc_lines(stderr):
    return [line for line in stderr.splitlines() if line.startswith("tapmc:")]


def test_every_package_is_required_or_optional_with_its_reason():
    rows = packages()
    assert rows and all(kind in ("required", "optional") and reason for kind, _, reason in rows)
    # the tests, the documentation and the fuzz test are optional; building is not
    assert {"libgtest-dev", "python3-pytest", "python3-sphinx", "python3-venv", "clang",
            "libclang-rt-dev"} <= set(package_list("optional"))
    assert {"build-essential", "cmake", "liblammps-dev", "libopenmpi-dev",
            "python3-numpy"} <= set(package_list("required"))


def test_nothing_missing_is_silent(fake):
    out, log = fake("install-deps.sh")
    assert (out.returncode, out.stdout, out.stderr, log) == (0, "", "", [])


def test_root_installs_every_missing_package(fake):
    missing = ["cmake", "clang", "libclang-rt-dev"]
    out, log = fake("install-deps.sh", missing, uid=0)
    assert out.returncode == 0, out.stderr
    assert out.stdout == ""   # nothing left missing
    assert tapmc_lines(out.stderr) == [
        "tapmc: installing missing Debian packages: cmake clang libclang-rt-dev"]
    assert log == ["apt-get update -qq", "apt-get install -y -qq --no-install-recommends "
                   "cmake clang libclang-rt-dev"]


def test_a_user_with_a_working_sudo_installs_through_it(fake):
    out, log = fake("install-deps.sh", ["python3-sphinx"], sudo="works")
    assert out.returncode == 0 and out.stdout == "", out.stderr
    assert tapmc_lines(out.stderr) == [
        "tapmc: installing missing Debian packages with sudo: python3-sphinx"]
    assert log[0] == "sudo apt-get update -qq" and log[1] == "apt-get update -qq", log


def test_missing_optional_packages_without_root_are_named_and_left_out(fake):
    """The QA's case: clang and libclang-rt-dev missing, no root, no sudo: one line naming them
    and what goes without them, no 'installing', and the build goes on."""
    out, log = fake("install-deps.sh", ["clang", "libclang-rt-dev", "python3-sphinx"])
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["python3-sphinx", "clang", "libclang-rt-dev"]
    lines = tapmc_lines(out.stderr)
    assert len(lines) == 1 and out.stderr.count("\n") == 1, out.stderr
    assert "installing" not in lines[0]
    assert "the fuzz test of the dump reader (clang libclang-rt-dev)" in lines[0]
    assert "the HTML pages (target doc) and their test (python3-sphinx)" in lines[0]
    assert log == []


def test_missing_required_packages_without_root_stop_with_the_line_for_an_admin(fake):
    out, log = fake("install-deps.sh", ["cmake", "liblammps-dev", "libgtest-dev"])
    assert out.returncode == 1
    assert out.stdout == ""
    text = " ".join(out.stderr.split())
    assert "installing" not in text
    assert "tapmc: required Debian packages are missing, for the build (cmake); the LAMMPS " \
        "library and CMake package that lmp_tapmc links with (liblammps-dev)\n" in out.stderr
    assert "not root, and no sudo that works" in text, text
    assert "\n  apt-get install --no-install-recommends cmake liblammps-dev libgtest-dev\n" \
        in out.stderr
    assert "doc/install.rst, route 1" in text
    assert log == []


def test_a_sudo_that_refuses_is_followed_by_a_tapmc_line(fake):
    out, log = fake("install-deps.sh", ["clang"], sudo="refuse")
    assert out.returncode == 0
    assert out.stdout.split() == ["clang"]
    lines = out.stderr.splitlines()
    refusal = next(k for k, line in enumerate(lines) if line.startswith("Sorry, user"))
    assert lines[refusal + 1].startswith("tapmc: sudo could not install them"), lines
    assert "the fuzz test of the dump reader (clang)" in lines[refusal + 2]
    assert log == ["sudo apt-get update -qq"]


def test_a_sudo_that_refuses_stops_at_missing_required_packages(fake):
    out, _ = fake("install-deps.sh", ["cmake"], sudo="refuse")
    assert out.returncode == 1
    assert "\n  apt-get install --no-install-recommends cmake\n" in out.stderr


@pytest.mark.parametrize("missing, gtests", [((), "ON"), (("libgtest-dev",), "OFF"),
                                             (("clang", "python3-pytest"), "ON")])
def test_build_leaves_out_the_googletest_suites_without_googletest(fake, missing, gtests):
    out, log = fake(str(Path("build.sh")), missing)
    assert out.returncode == 0, out.stderr
    configure = next(line for line in log if " -S " in line)
    assert f"-DTAPMC_BUILD_GTESTS={gtests}" in configure.split(), configure


@pytest.mark.skipif(os.geteuid() == 0 and not shutil.which("setpriv"),
                    reason="as root, setpriv is needed to run as the user nobody")
def test_as_the_user_nobody():
    """The real `id` of a user who is not root (nobody, through setpriv when the test runs as
    root), no sudo on PATH, a required and an optional package missing. The scripts run from a
    copy in a folder that nobody may read (pytest's folders are root's own)."""
    base = Path(tempfile.mkdtemp(prefix="tapmc_setup_"))
    try:
        shutil.copytree(SETUP, base / "setup")
        bin_dir = base / "bin"
        bin_dir.mkdir()
        for tool in TOOLS + ("id",):
            os.symlink(shutil.which(tool), bin_dir / tool)
        (bin_dir / "dpkg-query").write_text("#!/bin/sh\n" + FAKES["dpkg-query"] + "\n")
        for path in [base, *base.rglob("*")]:
            if not path.is_symlink():
                path.chmod(0o755)
        prefix = [shutil.which("setpriv"), "--reuid=65534", "--regid=65534", "--clear-groups"] \
            if os.geteuid() == 0 else []
        env = {"PATH": str(bin_dir), "FAKE_MISSING": "zlib1g-dev python3-venv"}
        out = subprocess.run([*prefix, str(base / "setup" / "install-deps.sh")], env=env,
                             capture_output=True, text=True, timeout=60,
                             stdin=subprocess.DEVNULL)
    finally:
        shutil.rmtree(base)
    assert out.returncode == 1, out.stderr
    assert "not root" in out.stderr and "installing" not in out.stderr
    assert "apt-get install --no-install-recommends zlib1g-dev python3-venv\n" in out.stderr
    assert re.search(r"left out .*the venv route", out.stderr), out.stderr


def test_without_network_the_fetch_says_the_archive_is_out_of_reach(tmp_path):
    """apt-get update cannot reach Debian's archive (a proxy on a closed port): the message says
    so and where the offline way is, not that the suite lacks the version."""
    env = {k: v for k, v in os.environ.items() if k.lower() not in ("no_proxy", "https_proxy")}
    env.update(http_proxy=NO_NETWORK, HTTP_PROXY=NO_NETWORK)
    version = "20220106.git7586adbb6a+ds1-2"
    env.setdefault("TAPMC_LAMMPS_SRC_VERSION", version)
    env["TAPMC_LAMMPS_SRC_SUITE"] = "bookworm"
    out = subprocess.run(["bash", str(SETUP / "fetch-lammps-headers.sh"), str(tmp_path / "h")],
                         env=env, capture_output=True, text=True, timeout=240,
                         stdin=subprocess.DEVNULL)
    assert out.returncode == 1
    text = " ".join(out.stderr.split())
    assert "Debian's archive is out of reach" in text, text
    assert f"a proxy in the way (http_proxy={NO_NETWORK})" in text
    assert "doc/install.rst, 'Without network'" in text
    assert "has no lammps=" not in text
    assert not (tmp_path / "h").exists()
    page = (SOURCE / "doc" / "install.rst").read_text()
    assert "\nWithout network\n" in page, "the section the message names"



def test_without_network_configuring_says_how_to_go_on_offline(tmp_path):
    """The same through CMake, for Debian's LAMMPS with no headers in TAPMC's cache (an empty
    HOME): the fetch's reason, then the offline way (-DTAPMC_LAMMPS_HEADERS_DIR)."""
    if subprocess.run(["dpkg-query", "-W", "liblammps-dev"], capture_output=True).returncode:
        pytest.skip("Debian's liblammps-dev is not installed: CMake fetches no headers")
    home = tmp_path / "home"
    home.mkdir()
    env = {k: v for k, v in os.environ.items()
           if k.lower() not in ("no_proxy", "https_proxy", "xdg_cache_home")
           and not k.startswith("TAPMC_")}
    env.update(HOME=str(home), http_proxy=NO_NETWORK, HTTP_PROXY=NO_NETWORK)
    out = subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(tmp_path / "build"),
                          "-DTAPMC_BUILD_TESTS=OFF", "-DTAPMC_BUILD_PORES=OFF",
                          "-DTAPMC_BUILD_BENCH=OFF"], env=env, capture_output=True, text=True,
                         timeout=300, stdin=subprocess.DEVNULL)
    assert out.returncode != 0, out.stdout
    text = " ".join(out.stderr.split())
    assert "Debian's archive is out of reach" in text, text
    assert "by hand once that is mended, or, offline, give -DTAPMC_LAMMPS_HEADERS_DIR=<" in text
    assert "or Give" not in text
