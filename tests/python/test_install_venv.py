# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The venv route of doc/install.rst, offline: `python3 -m venv --system-site-packages V` and
`V/bin/pip install --no-build-isolation --no-deps tools/python` (tools/python/pyproject.toml,
setuptools from Debian); then `import tapmc` in V, with PYTHONPATH unset, is the venv's copy,
with the one version (tapmc.__version__, also the distribution's metadata). pip builds in the
tree it is given, so the test installs a copy of tools/python and writes nothing into the
source tree."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
# Debian's interpreter (python3-venv, python3-setuptools, numpy, ...), as the page says
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


def test_pip_install_into_a_venv_offline(tmp_path):
    version = re.search(r'^__version__ = "([0-9.]+)"$',
                        (SOURCE / "tools/python/tapmc/__init__.py").read_text(), re.M).group(1)
    tree = tmp_path / "tools" / "python"
    shutil.copytree(SOURCE / "tools/python", tree,
                    ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    venv = tmp_path / "V"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(PIP_NO_INDEX="1", PIP_NO_CACHE_DIR="1", PIP_DISABLE_PIP_VERSION_CHECK="1")

    def run(*cmd):
        out = subprocess.run([str(c) for c in cmd], cwd=tmp_path, env=env, capture_output=True,
                             text=True, timeout=240, stdin=subprocess.DEVNULL)
        assert out.returncode == 0, f"{cmd}:\n{out.stdout}\n{out.stderr}"
        return out.stdout

    run(PYTHON, "-m", "venv", "--system-site-packages", venv)
    run(venv / "bin/pip", "install", "--no-build-isolation", "--no-deps", "tools/python")
    out = run(venv / "bin/python", "-c",
              "import importlib.metadata, tapmc, tapmc.paper.claims; print(tapmc.__file__); "
              "print(tapmc.__version__); print(importlib.metadata.version('tapmc'))")
    module, module_version, dist_version = out.split()
    assert Path(module).resolve().is_relative_to(venv.resolve()), module
    assert module_version == dist_version == version, out
    data = Path(module).parent / "paper" / "claims.toml"
    assert data.is_file(), "package data missing from the wheel: " + str(data)
    # The venv of a project under git (a project's .venv): the installed package has no
    # source tree, so its campaigns record no commit (they recorded the project's) and the
    # paper's defaults are the current directory's, not V/lib (where doc/ was written)
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-C", tmp_path]
    run(*git, "init", "-q")
    run(*git, "commit", "-q", "--allow-empty", "-m", "a project")
    out = run(venv / "bin/python", "-c",
              "from tapmc._source import source_tree, git_checkout; "
              "from tapmc.campaign.provenance import tapmc_version; "
              "from tapmc.paper import _runs; "
              "print(source_tree(), git_checkout(), tapmc_version(), _runs.SOURCE_DIR)")
    assert out.split() == ["None", "None", "None", "."], out


def test_the_source_tree_is_found_from_the_tree_itself():
    """Run from this tree (the suite's PYTHONPATH), the package knows its tree and, in a git
    checkout, describes it."""
    from tapmc._source import git_checkout, source_tree
    from tapmc.campaign.provenance import tapmc_version

    tree = Path(__file__).resolve().parents[2]
    assert source_tree() == tree
    if (tree / ".git").exists():
        assert git_checkout() == tree and tapmc_version()
