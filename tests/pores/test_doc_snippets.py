# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Every snippet of doc/tapmc-pores.rst runs as written: the `.. code-block:: sh` blocks with bash
# and the `.. code-block:: python` blocks with this Python (`text` blocks show usage and messages
# and are not run), in the order of the page, from a
# repository root whose build/ holds this build's lmp_tapmc and tapmc-pores. The root is a
# scratch directory (tests/ linked from the sources), so the outputs the snippets write in
# build/doc-pores are real outputs of the programs, checked below.
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
DOC = SOURCE / "doc" / "tapmc-pores.rst"
PORES = os.environ.get("TAPMC_PORES_EXE")
LMP = os.environ.get("TAPMC_LMP")


def snippets(text):
    """(language, code) of every code-block in the page, in order; a block preceded by the
    comment `.. snippet: skip <reason>` is left out."""
    blocks = []
    lines = text.splitlines()
    skip_next = False
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith(".. snippet: skip"):
            skip_next = True
        match = re.match(r"^(\s*)\.\. code-block:: *(\w+)", line)
        if match:
            indent, language = len(match.group(1)), match.group(2)
            i += 1
            body = []
            while i < len(lines) and (not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > indent):
                body.append(lines[i])
                i += 1
            code = "\n".join(body).strip("\n")
            width = min(len(l) - len(l.lstrip()) for l in code.splitlines() if l.strip())
            code = "\n".join(l[width:] for l in code.splitlines()) + "\n"
            if not skip_next:
                blocks.append((language, code))
            skip_next = False
            continue
        i += 1
    return blocks


def test_snippet_extraction_sees_every_block():
    blocks = snippets(DOC.read_text())
    languages = [language for language, _ in blocks]
    assert set(languages) <= {"sh", "python", "text"}, languages
    assert languages.count("sh") >= 2 and languages.count("python") >= 1
    assert all(code.strip() for _, code in blocks)


@pytest.mark.skipif(not (PORES and LMP), reason="needs TAPMC_PORES_EXE and TAPMC_LMP (lmp_tapmc built)")
def test_doc_snippets_run_as_written(tmp_path):
    root = tmp_path / "repo"
    (root / "build" / "tools" / "pores").mkdir(parents=True)
    os.symlink(SOURCE / "tests", root / "tests")
    os.symlink(LMP, root / "build" / "lmp_tapmc")
    os.symlink(PORES, root / "build" / "tools" / "pores" / "tapmc-pores")
    outputs = []
    for number, (language, code) in enumerate(snippets(DOC.read_text()), 1):
        if language == "text":
            continue
        command = ["bash", "-e", "-c", code] if language == "sh" else [sys.executable, "-c", code]
        result = subprocess.run(command, cwd=root, capture_output=True, text=True, timeout=300)
        assert result.returncode == 0, f"snippet {number} ({language}) failed:\n{code}\n{result.stderr}"
        # The examples are meant to show clean runs: no warning, no error.
        assert "warning" not in result.stderr.lower(), f"snippet {number}:\n{result.stderr}"
        outputs.append(result.stdout)
    made = root / "build" / "doc-pores"
    for name in ("fig10.hist.csv", "fig10.frame_hist.csv", "fig10.json", "fig9.p0.csv", "late.frames.csv",
                 "deep_box.hist.csv", "fig10.png", "fig9.png"):
        assert (made / name).stat().st_size > 0, name
    assert not list(made.glob("*.partial"))
    assert any("nu over all frames:" in out for out in outputs)
