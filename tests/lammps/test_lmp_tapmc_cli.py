# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# lmp_tapmc behaves like lmp: command-line switches, styles registered on every rank, and the
# TAPMC styles still known after `clear` (which rebuilds LAMMPS's style tables).
import subprocess

from lmprun import LMP, run_lammps

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


def test_help_lists_the_lammps_version():
    proc = subprocess.run([LMP, "-h"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=60)
    assert proc.returncode == 0
    assert "Large-scale Atomic/Molecular Massively Parallel Simulator" in proc.stdout


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
