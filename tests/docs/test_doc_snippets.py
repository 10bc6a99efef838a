# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Every code block of the documentation runs as written: README.md (fenced blocks) and every
# doc/*.rst page (`.. code-block::` directives and `::` literal blocks). One pytest case per
# block, named file:line, so a failure names the block.
#
# How each block runs: the blocks of one page run in document order in one temporary directory
# of that page, so a block may read what an earlier block of the same page wrote (run the whole
# file, not one block alone, when a block depends on another). The directory mirrors the
# repository root (a symbolic link to every top-level entry of the source tree, and `build` ->
# the build directory), so blocks are written as run from the repository root; PATH starts with
# the build directory and build/tools/pores; TAPMC_BUILD_DIR, TAPMC_SOURCE_DIR, TAPMC_LMP and
# TAPMC_LIB are exported. A block naming a program of an optional part of the build that was not
# built (tapmc-pores with TAPMC_BUILD_PORES=OFF) is skipped.
#
#   LAMMPS  (```lammps, `.. code-block:: LAMMPS`): $TAPMC_LMP -in the block -var taps 2. A block
#           without create_box/read_data/read_restart is a fragment: it runs after PREAMBLE (a
#           small periodic box with an open top, plus CREATE_SPHERES unless the block creates its
#           own spheres with create_packing/create_atoms), and `run 2` follows when it has no run
#           command. Long runs are written `run ${taps}` with `variable taps index N`: the
#           `-var taps 2` given here wins over the index value. A literal `run N` with N above
#           MAX_LITERAL_RUN fails the test. Blocks in a "Syntax" section describe syntax, not input,
#           and are not run.
#   python  (```python, `.. code-block:: python`): the Python that runs this file (under ctest the
#           project's TAPMC_PYTHON).
#   sh      (```sh, ```bash, `.. code-block:: sh` or bash): bash -e.
#   text    (```text, `.. code-block:: text`, also console/none): output or prose, not run.
# A block without a language (``` or `::`) fails: say what it is (one of the above).
# A block preceded by `.. snippet: skip <reason>` (rst comment) or `<!-- snippet: skip <reason> -->`
# (markdown) is skipped with that reason shown.
#
# Pages in PAGE_OUTPUTS show clean runs of programs that write files: each of their blocks must
# print no warning, and after the page's last block test_page_outputs checks the files the blocks
# wrote (see there).
import glob
import os
import re
import subprocess
import sys
import time

import pytest

SOURCE_DIR = os.path.abspath(os.environ.get(
    "TAPMC_SOURCE_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")))
BUILD_DIR = os.path.abspath(os.environ.get("TAPMC_BUILD_DIR", os.path.join(SOURCE_DIR, "build")))
LMP = os.environ.get("TAPMC_LMP", os.path.join(BUILD_DIR, "lmp_tapmc"))
LIB = os.environ.get("TAPMC_LIB", os.path.join(BUILD_DIR, "libtapmc.so"))
PYTHON = sys.executable

# Blocks in pages owned by work merged in parallel that fail today, keyed file:line. Each entry is
# reported as an expected failure; the list is emptied when that work is merged.
KNOWN_FAILURES_TO_FIX_AT_MERGE = {}

# The standard small scene of a LAMMPS fragment: 200 spheres of radius 0.5 (diameter 1) on a
# floor at z = 0, periodic sides of 8, open top; two atom types.
PREAMBLE = """units           lj
atom_style      sphere
boundary        p p fm
region          box block 0 8 0 8 0 30
create_box      2 box
"""
CREATE_SPHERES = "create_packing  200 1 0.5 4928 floor 0.0\n"
SMALL_RUN = 2
MAX_LITERAL_RUN = 100
TIMEOUT = 300  # seconds per block

# Programs of optional parts of the build: a block that names one is skipped when it is absent.
OPTIONAL_PROGRAMS = {"tapmc-pores": os.path.join(BUILD_DIR, "tools", "pores", "tapmc-pores")}

# Pages whose blocks write outputs, checked after the page's last block (test_page_outputs):
# the page has at least `blocks` runnable blocks of each language; the blocks wrote every file of
# `files` in `folder` (relative to the repository root), not empty, during this test session (the
# folder is in the build directory, where an earlier session left its outputs) and left no
# `*.partial` file there; one block printed `printed`.
PAGE_OUTPUTS = {
    os.path.join("doc", "tapmc-pores.rst"): {
        "blocks": {"sh": 2, "python": 1},
        "folder": os.path.join("build", "doc-pores"),
        "files": ("fig10.hist.csv", "fig10.frame_hist.csv", "fig10.json", "fig9.p0.csv",
                  "late.frames.csv", "deep_box.hist.csv", "fig10.png", "fig9.png"),
        "printed": "nu over all frames:",
    },
    os.path.join("doc", "tutorial.rst"): {
        "blocks": {"lammps": 1, "sh": 2, "python": 2},
        "folder": "",
        "files": ("tutorial.log", "tutorial.taps.dat", "tutorial.profile.dat", "tutorial.0.dump",
                  "tutorial.compaction.png", "tutorial.compaction.csv",
                  "tutorial.profile.png", "tutorial.pores.hist.csv", "tutorial.pores.png"),
        "printed": "mean normalised pore volume nu:",
    },
}

RUNNABLE = {"lammps": "lammps", "python": "python", "python3": "python", "sh": "sh",
            "bash": "sh", "shell": "sh"}
NOT_CODE = {"text", "console", "none", "output", "rst"}


class Block:
    def __init__(self, path, line, language, code, section, skip_reason):
        self.path = path              # relative to the source tree
        self.line = line              # 1-based line of the directive / opening fence
        self.language = language      # lower case, or None when the block has none
        self.code = code
        self.section = section
        self.skip_reason = skip_reason

    @property
    def name(self):
        return "%s:%d" % (self.path, self.line)


SKIP_RST = re.compile(r"^\s*\.\.\s+snippet:\s*skip\b\s*(.*)$")
SKIP_MD = re.compile(r"^\s*<!--\s*snippet:\s*skip\b\s*(.*?)\s*-->\s*$")
DIRECTIVE = re.compile(r"^(\s*)\.\.\s+(code-block|code|sourcecode)::\s*(\S*)\s*$")
OTHER_DIRECTIVE = re.compile(r"^\s*\.\.\s+[\w:-]+::")
UNDERLINE = re.compile(r"^([=\-`:'\"~^_*+#<>])\1{2,}\s*$")
FENCE = re.compile(r"^(\s*)(```+|~~~+)\s*([^\s`]*)")


def indent_of(line):
    return len(line) - len(line.lstrip())


def skip_marker_before(lines, k, pattern):
    """Reason of a skip marker on the nearest non-blank line before line k, else None."""
    k -= 1
    while k >= 0 and not lines[k].strip():
        k -= 1
    if k >= 0:
        m = pattern.match(lines[k])
        if m:
            return m.group(1).strip() or "no reason given"
    return None


def indented_body(lines, start, base_indent):
    """The block of lines after `start` indented deeper than base_indent (blank lines inside
    included), with the common indentation removed. Returns (code, index after the block)."""
    k = start
    body = []
    while k < len(lines):
        if lines[k].strip() and indent_of(lines[k]) <= base_indent:
            break
        body.append(lines[k])
        k += 1
    while body and not body[-1].strip():
        body.pop()
    while body and not body[0].strip():
        body.pop(0)
    common = min((indent_of(l) for l in body if l.strip()), default=0)
    return "\n".join(l[common:] for l in body) + "\n", k


def rst_blocks(path):
    rel = os.path.relpath(path, SOURCE_DIR)
    with open(path) as f:
        lines = f.read().splitlines()
    blocks = []
    section = ""
    k = 0
    while k < len(lines):
        line = lines[k]
        # A section title: a text line underlined by punctuation at least as long.
        if (k + 1 < len(lines) and line.strip() and not line.startswith(" ")
                and UNDERLINE.match(lines[k + 1]) and len(lines[k + 1].strip()) >= len(line.strip())):
            section = line.strip()
            k += 2
            continue
        m = DIRECTIVE.match(line)
        literal = (not m and line.rstrip().endswith("::") and not OTHER_DIRECTIVE.match(line)
                   and not SKIP_RST.match(line))
        if not m and not literal:
            k += 1
            continue
        if m:
            language = m.group(3).lower() or None
            base = len(m.group(1))
            marker_line = k
            start = k + 1
            # directive options (:linenos: etc.) come before the body
            while start < len(lines) and re.match(r"^\s+:[\w-]+:", lines[start]):
                start += 1
        else:
            language = None
            # "Text::" ends a paragraph: the block's indentation is relative to that paragraph.
            para = k
            while para > 0 and lines[para - 1].strip() and not lines[para - 1].lstrip().startswith(".."):
                para -= 1
            base = indent_of(lines[para])
            marker_line = para
            start = k + 1
        code, end = indented_body(lines, start, base)
        if code.strip():
            blocks.append(Block(rel, k + 1, language, code, section,
                                skip_marker_before(lines, marker_line, SKIP_RST)))
        k = max(end, k + 1)
    return blocks


def markdown_blocks(path):
    rel = os.path.relpath(path, SOURCE_DIR)
    with open(path) as f:
        lines = f.read().splitlines()
    blocks = []
    section = ""
    k = 0
    while k < len(lines):
        line = lines[k]
        if line.startswith("#"):
            section = line.lstrip("#").strip()
        m = FENCE.match(line)
        if not m:
            k += 1
            continue
        fence = m.group(2)
        end = k + 1
        while end < len(lines) and not lines[end].strip().startswith(fence):
            end += 1
        code = "\n".join(lines[k + 1:end]) + "\n"
        blocks.append(Block(rel, k + 1, m.group(3).lower() or None, code, section,
                            skip_marker_before(lines, k, SKIP_MD)))
        k = end + 1
    return blocks


def all_blocks():
    blocks = markdown_blocks(os.path.join(SOURCE_DIR, "README.md"))
    for page in sorted(glob.glob(os.path.join(SOURCE_DIR, "doc", "*.rst"))):
        blocks += rst_blocks(page)
    return blocks


BLOCKS = all_blocks()


def repository_mirror(workdir):
    """Make workdir look like the repository root with the build in build/."""
    for entry in os.listdir(SOURCE_DIR):
        if entry in ("build", ".git") or entry.startswith("build-"):
            continue
        os.symlink(os.path.join(SOURCE_DIR, entry), os.path.join(workdir, entry))
    os.symlink(BUILD_DIR, os.path.join(workdir, "build"))


def snippet_environment():
    env = dict(os.environ)
    env.update(TAPMC_BUILD_DIR=BUILD_DIR, TAPMC_SOURCE_DIR=SOURCE_DIR, TAPMC_LMP=LMP,
               TAPMC_LIB=LIB)
    env["PATH"] = os.pathsep.join([BUILD_DIR, os.path.join(BUILD_DIR, "tools", "pores"),
                                   env.get("PATH", "")])
    # The tapmc package of this tree, whatever tree the user-site tapmc.pth points at.
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [os.path.join(SOURCE_DIR, "tools", "python"),
                                                      env.get("PYTHONPATH")]))
    return env


def commands(code):
    """First words of the LAMMPS commands of a block (comments and continuations handled)."""
    words = []
    for line in code.replace("&\n", " ").splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            words.append(line.split())
    return words


def lammps_input(code):
    """The input run for a LAMMPS block (see the header), or raise ValueError."""
    cmds = commands(code)
    names = [c[0] for c in cmds]
    for c in cmds:
        if c[0] == "run" and len(c) > 1 and c[1].isdigit() and int(c[1]) > MAX_LITERAL_RUN:
            raise ValueError("`run %s` is too long for a test: write `run ${taps}` with `variable "
                             "taps index %s` (the test gives -var taps %d), or add a skip marker"
                             % (c[1], c[1], SMALL_RUN))
    text = code
    if not {"create_box", "read_data", "read_restart"} & set(names):
        spheres = "" if {"create_packing", "create_atoms"} & set(names) else CREATE_SPHERES
        text = PREAMBLE + spheres + code
    if "run" not in names:
        text += "run %d\n" % SMALL_RUN
    return text


def run_block(block, workdir):
    env = snippet_environment()
    if block.language == "lammps":
        with open(os.path.join(workdir, "in.snippet"), "w") as f:
            f.write(lammps_input(block.code))
        cmd = [LMP, "-in", "in.snippet", "-var", "taps", str(SMALL_RUN), "-nocite"]
    elif block.language == "python":
        with open(os.path.join(workdir, "snippet.py"), "w") as f:
            f.write(block.code)
        cmd = [PYTHON, "snippet.py"]
    else:
        with open(os.path.join(workdir, "snippet.sh"), "w") as f:
            f.write(block.code)
        cmd = ["bash", "-e", "snippet.sh"]
    proc = subprocess.run(cmd, cwd=workdir, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT,
                          stdin=subprocess.DEVNULL)
    return proc.returncode, proc.stdout


def block_param(block):
    marks = []
    if block.name in KNOWN_FAILURES_TO_FIX_AT_MERGE:
        marks.append(pytest.mark.xfail(reason=KNOWN_FAILURES_TO_FIX_AT_MERGE[block.name],
                                       strict=False))
    return pytest.param(block, id=block.name, marks=marks)


def missing_optional_program(code):
    """(program, path) of a program of an optional part of the build that the code names and
    that was not built, else None."""
    for program, path in OPTIONAL_PROGRAMS.items():
        if re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(program), code) and \
                not os.path.exists(path):
            return program, path
    return None


PAGE_DIRS = {}
PAGE_STARTS = {}   # page -> time.time() before its first block ran
PAGE_PRINTED = {}  # page -> outputs of its blocks, in order


def page_directory(block, tmp_path_factory):
    """The working directory shared by the blocks of block's page, made on first use."""
    if block.path not in PAGE_DIRS:
        path = tmp_path_factory.mktemp(re.sub(r"\W", "_", block.path))
        repository_mirror(str(path))
        PAGE_DIRS[block.path] = str(path)
        PAGE_STARTS[block.path] = time.time()
    return PAGE_DIRS[block.path]


@pytest.mark.parametrize("block", [block_param(b) for b in BLOCKS])
def test_doc_block_runs(block, tmp_path_factory):
    if block.skip_reason:
        pytest.skip("snippet: skip " + block.skip_reason)
    if block.language is None:
        pytest.fail("%s: a code block without a language: mark it python, sh, LAMMPS (run as a "
                    "test) or text (not run)" % block.name)
    lang = RUNNABLE.get(block.language, block.language)
    if lang in NOT_CODE:
        pytest.skip("%s block, not run" % block.language)
    if lang == "lammps" and block.section == "Syntax":
        pytest.skip("syntax description, not an input")
    if lang not in ("lammps", "python", "sh"):
        pytest.fail("%s: unknown language '%s' (python, sh, bash, LAMMPS, or text)"
                    % (block.name, block.language))
    missing = missing_optional_program(block.code)
    if missing:
        pytest.skip("%s is not built (%s)" % missing)
    block.language = lang
    try:
        rc, out = run_block(block, page_directory(block, tmp_path_factory))
    except ValueError as err:
        pytest.fail("%s: %s" % (block.name, err))
    assert rc == 0, "%s (%s) exited with %d:\n%s\n--- output (last 60 lines):\n%s" % (
        block.name, lang, rc, block.code, "\n".join(out.splitlines()[-60:]))
    if block.path in PAGE_OUTPUTS:
        PAGE_PRINTED.setdefault(block.path, []).append(out)
        # The page shows clean runs: no warning, no error.
        assert "warning" not in out.lower(), "%s printed a warning:\n%s" % (block.name, out)


# Runs after test_doc_block_runs (pytest keeps the order of the file).
@pytest.mark.parametrize("page", sorted(PAGE_OUTPUTS))
def test_page_outputs(page):
    expected = PAGE_OUTPUTS[page]
    languages = [RUNNABLE.get(b.language, b.language) for b in BLOCKS
                 if b.path == page and not b.skip_reason]
    for language, count in expected["blocks"].items():
        assert languages.count(language) >= count, \
            "%s: %d %s blocks, expected at least %d" % (page, languages.count(language),
                                                        language, count)
    missing = missing_optional_program("".join(b.code for b in BLOCKS if b.path == page))
    if missing:
        pytest.skip("%s is not built (%s)" % missing)
    if page not in PAGE_DIRS:
        pytest.skip("the blocks of %s did not run in this session: run the whole file" % page)
    folder = os.path.join(PAGE_DIRS[page], expected["folder"])
    # one second of slack for file systems whose clock lags time.time(); an earlier session's
    # outputs are older than that
    since = PAGE_STARTS[page] - 1.0
    for name in expected["files"]:
        path = os.path.join(folder, name)
        assert os.path.isfile(path), "%s: the blocks did not write %s" % (page, name)
        assert os.path.getsize(path) > 0, "%s: %s is empty" % (page, name)
        assert os.path.getmtime(path) >= since, \
            "%s: %s was not written by this session's blocks" % (page, name)
    partial = [p for p in glob.glob(os.path.join(folder, "*.partial"))
               if os.path.getmtime(p) >= since]
    assert not partial, "%s: unfinished outputs left: %s" % (page, partial)
    assert any(expected["printed"] in out for out in PAGE_PRINTED.get(page, [])), \
        "%s: no block printed %r" % (page, expected["printed"])


def test_every_page_was_read():
    """The extraction found the blocks of the pages that certainly have some."""
    paths = {b.path for b in BLOCKS}
    assert "README.md" in paths
    assert os.path.join("doc", "user_guide.rst") in paths


# The documentation cites the paper and the project's own files, never notes kept outside the
# repository (a *.md file that is not in it) or paths of one machine.
MACHINE_PATH = re.compile(r"\.\./shared/|(?<![\w.~])/(?:work|tmp|home|root)/")
MARKDOWN_NAME = re.compile(r"[\w.-]+\.md\b")
DOC_FILES = ["README.md", os.path.join("bench", "README.md")] + sorted(
    os.path.relpath(p, SOURCE_DIR) for p in glob.glob(os.path.join(SOURCE_DIR, "doc", "*.rst")))


def markdown_files_in_repository():
    names = set()
    for root, dirs, files in os.walk(SOURCE_DIR):
        dirs[:] = [d for d in dirs if d != ".git" and not d.startswith("build")]
        names.update(f for f in files if f.endswith(".md"))
    return names


@pytest.mark.parametrize("doc", [pytest.param(d, marks=[pytest.mark.xfail(
    reason=KNOWN_FAILURES_TO_FIX_AT_MERGE[d], strict=False)] if d in KNOWN_FAILURES_TO_FIX_AT_MERGE
    else []) for d in DOC_FILES])
def test_docs_cite_no_private_files_or_machine_paths(doc):
    ours = markdown_files_in_repository()
    with open(os.path.join(SOURCE_DIR, doc)) as f:
        hits = ["%s:%d: %s" % (doc, n, line.strip()) for n, line in enumerate(f, 1)
                if MACHINE_PATH.search(line)
                or any(name not in ours for name in MARKDOWN_NAME.findall(line))]
    assert not hits, "cite the paper (section, equation) or the project's own files:\n" + \
        "\n".join(hits)


SAMPLE_RST = '''Title
=====

Syntax
""""""

.. code-block:: LAMMPS

   fix ID group tapdilate eps

Examples
""""""""

.. snippet: skip needs an hour

.. code-block:: LAMMPS

   run 4000

Text::

   untyped

.. code-block:: python
   :linenos:

   print(1)
   if True:
       print(2)
'''

SAMPLE_MD = """# T

<!-- snippet: skip installs packages -->
```sh
tools/setup.sh
```

```
untyped
```
"""


def test_blocks_are_found_with_language_line_section_and_skip_marker(tmp_path):
    (tmp_path / "page.rst").write_text(SAMPLE_RST)
    (tmp_path / "page.md").write_text(SAMPLE_MD)
    rst = [(b.line, b.language, b.section, b.skip_reason, b.code)
           for b in rst_blocks(str(tmp_path / "page.rst"))]
    assert rst == [(7, "lammps", "Syntax", None, "fix ID group tapdilate eps\n"),
                   (16, "lammps", "Examples", "needs an hour", "run 4000\n"),
                   (20, None, "Examples", None, "untyped\n"),
                   (24, "python", "Examples", None, "print(1)\nif True:\n    print(2)\n")]
    md = [(b.line, b.language, b.skip_reason, b.code) for b in markdown_blocks(str(tmp_path / "page.md"))]
    assert md == [(4, "sh", "installs packages", "tools/setup.sh\n"), (8, None, None, "untyped\n")]


def test_lammps_fragments_get_the_preamble_and_a_short_run():
    fragment = lammps_input("fix tap all tapdilate 0.01 floor 0.0\n")
    assert fragment.startswith(PREAMBLE + CREATE_SPHERES) and fragment.endswith("run 2\n")
    own_spheres = lammps_input("create_packing 10 1 0.5 7\nrun ${taps}\n")
    assert own_spheres == PREAMBLE + "create_packing 10 1 0.5 7\nrun ${taps}\n"
    whole = "units lj\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\nrun 0\n"
    assert lammps_input(whole) == whole
    with pytest.raises(ValueError, match="run \\$\\{taps\\}"):
        lammps_input("run 4000\n")
