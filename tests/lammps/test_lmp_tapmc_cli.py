# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# lmp_tapmc behaves like lmp: command-line switches, styles registered on every rank, and the
# TAPMC styles still known after `clear` (which rebuilds LAMMPS's style tables), `-h` listing the
# TAPMC styles, and LAMMPS's citation reminder naming the paper.
import os
import re
import subprocess
import tempfile
from pathlib import Path

from lmprun import LMP, MPIRUN, run_lammps

SCRIPT = """units lj
atom_style sphere
atom_modify map array
boundary p p fm
region box block 0 6 0 6 0 8
create_box 1 box
create_atoms 1 single 1 1 2
set group all diameter 1.0
fix tap all tapdilate ${eps} floor 0.0
run 1
variable z equal z[1]
print "HEIGHT ${z}"
"""


def help_text(*args, nprocs=1):
    cmd = [LMP, *args]
    if nprocs > 1:
        cmd = MPIRUN + ["-np", str(nprocs)] + cmd
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=60, cwd=tempfile.mkdtemp(prefix="tapmc_"),
                          stdin=subprocess.DEVNULL)
    return proc.returncode, proc.stdout


def test_help_lists_the_lammps_version():
    rc, out = help_text("-h")
    assert rc == 0
    assert "Large-scale Atomic/Molecular Massively Parallel Simulator" in out


def test_help_lists_the_tapmc_styles_after_lammps_own():
    # LAMMPS's help lists the styles compiled into the library; lmp_tapmc adds a section with
    # its own, in the same layout (names in columns of 16), after LAMMPS's lists.
    for flag in ("-h", "-help"):
        rc, out = help_text(flag)
        assert rc == 0, out
        lines = out.splitlines()
        start = lines.index("TAPMC styles (registered by lmp_tapmc at start-up, not in the "
                            "lists above):")
        assert start > lines.index("* Command styles")
        section = lines[start:]
        for category, names in (("Fix", ["tapdilate", "mc/settle"]),
                                ("Compute", ["stereo/profile", "contacts"]),
                                ("Command", ["create_packing"])):
            k = section.index(f"* {category} styles (TAPMC)")
            assert section[k + 2].split() == names, section
        for style in ("fix tapdilate", "fix mc/settle", "compute stereo/profile",
                      "compute contacts", "command create_packing"):
            assert any(line.split()[:2] == style.split() for line in section), style


def test_help_names_the_commit_the_binary_was_built_from():
    """'TAPMC build: <git describe>' (a campaign records it with each attempt): a commit of
    this repository when built from a git checkout, 'unknown' otherwise."""
    rc, out = help_text("-h")
    assert rc == 0, out
    (line,) = [line for line in out.splitlines() if line.startswith("TAPMC build: ")]
    build = line.split()[2]
    source = Path(__file__).resolve().parents[2]
    if not (source / ".git").exists():
        assert build == "unknown"
        return
    name = re.sub(r"-dirty$", "", build)
    name = re.sub(r"^.*-g([0-9a-f]{7,40})$", r"\1", name)   # tag-N-g<hash>: the hash
    known = subprocess.run(["git", "-C", str(source), "cat-file", "-e", name + "^{commit}"],
                           capture_output=True)
    assert known.returncode == 0, f"{build}: not a commit of {source}"


def test_help_section_once_on_several_ranks_and_never_after_an_error():
    rc, out = help_text("-h", nprocs=2)
    assert rc == 0, out
    assert out.count("TAPMC styles (registered by lmp_tapmc") == 1
    rc, out = help_text("-h", "-no-such-switch")
    assert rc != 0 and "Invalid command-line argument" in out
    assert "TAPMC styles" not in out
    # "-h" as the value of a switch asks for no help
    rc, out = help_text("-var", "x", "-h", "-log", "none", "-nocite", "-in", "/dev/null")
    assert rc == 0 and "TAPMC styles" not in out


CITATION = ("TAPMC package (fix tapdilate, fix mc/settle, compute stereo/profile, "
            "compute contacts, create_packing)")
PAPER = "title = {Numerical model for granular compaction under vertical tapping}"
ONE_ATOM = "create_atoms 1 single 1 1 0.5\nset group all diameter 1.0\n"
CITED_STYLES = {
    "create_packing": "create_packing 20 1 0.5 7\n",
    "compute stereo/profile": ONE_ATOM + "compute phi all stereo/profile\nrun 0\n",
    "compute contacts": ONE_ATOM + "compute z all contacts 0.01\nrun 0\n",
    "fix tapdilate": ONE_ATOM + "fix tap all tapdilate 0.01\nrun 0\n",
    "fix mc/settle": ONE_ATOM + "fix settle all mc/settle 7\nrun 0\n",
}


def run_cited(body, *switches):
    workdir = tempfile.mkdtemp(prefix="tapmc_")
    with open(os.path.join(workdir, "in.cite"), "w") as f:
        f.write("units lj\natom_style sphere\nboundary p p fm\n"
                "region box block 0 4 0 4 0 12\ncreate_box 1 box\n" + body)
    proc = subprocess.run([LMP, "-in", "in.cite", *switches], cwd=workdir,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=120, stdin=subprocess.DEVNULL)
    assert proc.returncode == 0, proc.stdout

    def read(name):
        path = os.path.join(workdir, name)
        return open(path).read() if os.path.exists(path) else None
    return proc.stdout, read("log.lammps"), read("papers.cite")


def test_each_style_cites_the_paper_once():
    # LAMMPS's reminder: the terse line on the screen, the BibTeX entry in the log file
    for style, body in CITED_STYLES.items():
        screen, log, _ = run_cited(body)
        assert "CITE-CITE-CITE" in screen, style
        assert screen.count(CITATION) == 1, (style, screen)
        assert PAPER in log and "doi = {10.1103/PhysRevE.63.051304}" in log, style
    # all five in one run: listed once
    screen, log, _ = run_cited("".join(CITED_STYLES.values()).replace(ONE_ATOM, ""))
    assert screen.count(CITATION) == 1 and log.count(PAPER) == 1


def test_cite_file_and_nocite():
    screen, _, cite = run_cited(CITED_STYLES["fix tapdilate"], "-cite", "papers.cite")
    assert "The file papers.cite lists these citations in BibTeX format." in screen
    assert CITATION in cite and PAPER in cite
    screen, log, cite = run_cited(CITED_STYLES["fix tapdilate"], "-nocite")
    assert cite is None
    for text in (screen, log):
        assert "CITE-CITE" not in text and CITATION not in text and PAPER not in text


def test_var_switch_and_clear():
    rc, out, _ = run_lammps(SCRIPT + "clear\n" + SCRIPT.replace("${eps}", "1.0"),
                            variables={"eps": 0.5})
    assert rc == 0, out
    heights = [float(line.split()[1]) for line in out.splitlines() if line.startswith("HEIGHT")]
    assert heights == [3.0, 4.0]


def test_styles_registered_on_every_rank():
    rc, out, _ = run_lammps(SCRIPT, nprocs=3, variables={"eps": 0.5})
    assert rc == 0, out
    assert "HEIGHT 3" in out


def test_unknown_style_message_is_lammps_own():
    rc, out, _ = run_lammps("units lj\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\n"
                            "fix f all tapdilatation 0.1\n")
    assert rc != 0 and "Unrecognized fix style 'tapdilatation'" in out
