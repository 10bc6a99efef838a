# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.paper: the paper's figures, one command each (``tapmc-paper fig2`` ... ``fig10``).

Each figure module ``tapmc.paper.figN`` exposes ``runs(scale, seeds) -> list[RunSpec]`` (the
LAMMPS runs it needs, see :mod:`tapmc.campaign`) and ``draw(campaign, out_dir) -> (png, csv)``.
:mod:`tapmc.paper.scales` holds the QUICK and FULL presets; :mod:`tapmc.paper.cli` is the
command line.
"""

#: Figure subcommands, in the paper's order (Fig. 1 is a drawing of a trial move).
FIGURES = ("fig2", "fig3", "fig4", "fig5", "fig6", "fig7", "fig8", "fig9", "fig10")
