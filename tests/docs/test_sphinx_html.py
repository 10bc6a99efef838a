# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The documentation builds as HTML with Debian's Sphinx (python3-sphinx, installed by the setup)
# without a warning: every page is in a toctree of doc/index.rst, every cross-reference resolves,
# every code block lexes. The same build as `cmake --build build --target doc`, into fresh
# directories of this test: an incremental build would not repeat the warnings of pages that did
# not change.
import glob
import os
import re
import subprocess
import sys

SOURCE_DIR = os.path.abspath(os.environ.get(
    "TAPMC_SOURCE_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")))
DOC = os.path.join(SOURCE_DIR, "doc")
TIMEOUT = 240  # seconds; the build takes about 10 s on one core


def pages():
    """Every page of the documentation: doc/*.rst and the pages in its subfolders (not in the
    campaigns' data), as Sphinx document names."""
    found = []
    for path in glob.glob(os.path.join(DOC, "**", "*.rst"), recursive=True):
        name = os.path.relpath(path, DOC)[:-len(".rst")]
        if not name.startswith(os.path.join("validation", "")):
            found.append(name)
    return sorted(found)


def version():
    with open(os.path.join(SOURCE_DIR, "tools", "python", "tapmc", "__init__.py")) as f:
        return re.search(r'^__version__ = "([0-9.]+)"$', f.read(), re.M).group(1)


def test_html_builds_without_warnings_and_has_every_page(tmp_path):
    html = tmp_path / "doc-html"
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
           "-d", str(tmp_path / "doc-doctrees"), DOC, str(html)]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=TIMEOUT, stdin=subprocess.DEVNULL)
    assert proc.returncode == 0, "%s exited with %d (warnings are errors):\n%s" % (
        " ".join(cmd), proc.returncode, proc.stdout)
    index = (html / "index.html").read_text()
    assert "TAPMC %s" % version() in index
    names = pages()
    assert "index" in names and "fix_mc_settle" in names and "measurements" in names, names
    missing = [n for n in names if not (html / (n + ".html")).is_file()]
    assert not missing, "pages without HTML: %s" % missing
    # every page is reachable from the front page's tables of contents
    unlinked = [n for n in names if n != "index" and 'href="%s.html' % n not in index]
    assert not unlinked, "pages not in a toctree of doc/index.rst: %s" % unlinked
