// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Registration of the TAPMC styles in a running LAMMPS instance (no PLUGIN package needed).
#ifndef TAPMC_REGISTER_STYLES_H
#define TAPMC_REGISTER_STYLES_H

#include <cstdio>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace tapmc {
// Insert every TAPMC fix, compute and command creator into lmp's style maps, and wrap the
// box-creating commands (create_box, read_data, read_restart) so that the styles are inserted
// again after a `clear` (which rebuilds Modify and forgets them). Idempotent.
void register_styles(LAMMPS_NS::LAMMPS *lmp);
// Writes the "TAPMC styles" section of `lmp_tapmc -h`: the TAPMC styles by category, in the
// columns of LAMMPS's own help, then one line per style with what it does.
void print_styles_help(std::FILE *out);
}  // namespace tapmc

extern "C" {
// For Python: ctypes.CDLL("libtapmc.so").tapmc_register(lammps.lammps().lmp). Returns 0.
int tapmc_register(void *lmp);
// For PLUGIN-enabled LAMMPS builds: `plugin load libtapmc.so`.
void lammpsplugin_init(void *lmp, void *handle, void *regfunc);
}

#endif
