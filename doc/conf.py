# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Sphinx configuration of the HTML pages (Debian's python3-sphinx): `cmake --build build --target
# doc` builds them into build/doc-html; tests/docs/test_sphinx_html.py builds them with warnings
# as errors.
import os
import re

from docutils import nodes
from pygments import token
from pygments.lexer import RegexLexer, bygroups

_HERE = os.path.dirname(os.path.abspath(__file__))


def _tapmc_version():
    """__version__ of the Python package tapmc, the one version of TAPMC."""
    path = os.path.join(_HERE, "..", "tools", "python", "tapmc", "__init__.py")
    with open(path) as f:
        match = re.search(r'^__version__ = "([0-9]+\.[0-9]+\.[0-9]+)"$', f.read(), re.M)
    if not match:
        raise RuntimeError('%s has no line __version__ = "X.Y.Z"' % path)
    return match.group(1)


project = "TAPMC"
author = "the TAPMC developers"
copyright = "the TAPMC developers; the model: P. Philippe and D. Bideau, Phys. Rev. E 63, 051304 (2001)"
version = release = _tapmc_version()

root_doc = "index"
source_suffix = {".rst": "restructuredtext"}
# The campaigns' run data and the figures' data files are not pages (the figures are found
# through the pages' image directives).
exclude_patterns = ["validation/data", "validation/front", "paper_scale/validation"]
# `::` blocks are output or prose unless they say otherwise (code-block:: LAMMPS, sh, python).
highlight_language = "none"

html_theme = "alabaster"
html_title = "TAPMC %s" % version
html_show_sourcelink = False
html_copy_source = False  # the .rst pages are installed beside the HTML
html_theme_options = {"description": "granular compaction under vertical tapping, for LAMMPS",
                      "page_width": "1100px", "body_max_width": "none"}

# Pages of the LAMMPS manual that the command pages cite as :doc:`...` (as the LAMMPS manual's
# own pages do): they link to the online manual. Any other unknown page stays an error.
LAMMPS_MANUAL = "https://docs.lammps.org/"
LAMMPS_PAGES = {
    "Howto_output", "atom_style", "boundary", "comm_modify", "compute", "compute_chunk_atom",
    "fix_ave_atom", "fix_ave_histo", "group",
    "create_atoms", "create_box", "displace_atoms", "dump", "fix", "fix_ave_time", "fix_print",
    "package", "plugin", "processors", "read_data", "read_restart", "region", "run",
    "reset_timestep", "thermo_style", "variable", "write_data", "write_restart",
}


def _lammps_manual_link(app, env, node, contnode):
    if node.get("refdomain") != "std" or node.get("reftype") != "doc":
        return None
    target = node.get("reftarget", "")
    if target not in LAMMPS_PAGES:
        return None
    link = nodes.reference("", "", internal=False, refuri=LAMMPS_MANUAL + target + ".html")
    link += contnode
    return link


class LammpsInputLexer(RegexLexer):
    """LAMMPS input scripts: a command word at the start of each line, then its arguments;
    comments, numbers, variable references (${name}, $x, v_, c_, f_) and quoted strings."""

    name = "LAMMPS input"
    aliases = ["lammps"]
    flags = re.MULTILINE
    tokens = {
        "root": [
            (r"#.*$", token.Comment.Single),
            (r"^([ \t]*)([A-Za-z_][\w/]*)", bygroups(token.Whitespace, token.Keyword)),
            (r"\$\{\w+\}|\$\w|\b[vcf]_\w+(\[[^\]\s]*\])?", token.Name.Variable),
            (r'"[^"\n]*"|\'[^\'\n]*\'', token.String),
            (r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?(?![\w.])", token.Number),
            (r"&[ \t]*$", token.Punctuation),
            (r"[ \t]+", token.Whitespace),
            (r"\n", token.Whitespace),
            (r"[^\s#$\"']+", token.Text),
            (r".", token.Text),
        ],
    }


def setup(app):
    # code-block:: LAMMPS (the LAMMPS manual's spelling) and lammps
    app.add_lexer("LAMMPS", LammpsInputLexer)
    app.add_lexer("lammps", LammpsInputLexer)
    app.connect("missing-reference", _lammps_manual_link)
