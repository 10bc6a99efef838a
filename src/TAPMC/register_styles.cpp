// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The one table of TAPMC styles. Adding a style: include its header and add it to a list below.
#include "register_styles.h"
#include "tapmc_build_id.h"  // generated at build time (cmake/TAPMCBuildId.cmake)

#include "command.h"
#include "compute.h"
#include "fix.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"

#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "compute_contacts.h"
#include "compute_stereo_profile.h"
#include "create_packing.h"
#include "fix_mc_settle.h"
#include "fix_tapdilate.h"

using namespace LAMMPS_NS;

namespace {

template <typename T> Fix *fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Compute *compute_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <typename T> Command *command_creator(LAMMPS *lmp)
{
  return new T(lmp);
}

struct FixEntry {
  const char *name;
  Modify::FixCreator creator;
  const char *info;
};
struct ComputeEntry {
  const char *name;
  Modify::ComputeCreator creator;
  const char *info;
};
struct CommandEntry {
  const char *name;
  Input::CommandCreator creator;
  const char *info;
};

const FixEntry kFixes[] = {
    {"tapdilate", &fix_creator<FixTapDilate>, "tap: homothetic vertical dilation about the floor"},
    {"mc/settle", &fix_creator<FixMCSettle>, "redeposition: biased hard-sphere Monte Carlo"},
};
const ComputeEntry kComputes[] = {
    {"stereo/profile", &compute_creator<ComputeStereoProfile>,
     "exact stereological packing-fraction profiles"},
    {"contacts", &compute_creator<ComputeContacts>,
     "coordination numbers within a gap, their mean and distribution"},
};
const CommandEntry kCommands[] = {
    {"create_packing", &command_creator<CreatePacking>,
     "initial packing by sequential gravitational deposition (Jullien-Meakin)"},
};

// Box-creating commands wrapped so that a `clear` (new Modify, empty of our styles) is followed
// by a re-registration before any fix or compute can be defined: every input defines its box
// with one of these before the first fix.
const char *const kBoxCommands[] = {"create_box", "read_data", "read_restart"};
std::map<std::string, Input::CommandCreator> &original_box_creators()
{
  static std::map<std::string, Input::CommandCreator> originals;
  return originals;
}

void insert_fix_and_compute_styles(LAMMPS *lmp)
{
  for (const auto &f : kFixes) (*lmp->modify->fix_map)[f.name] = f.creator;
  for (const auto &c : kComputes) (*lmp->modify->compute_map)[c.name] = c.creator;
}

template <int I> Command *box_command_creator(LAMMPS *lmp)
{
  insert_fix_and_compute_styles(lmp);
  return original_box_creators().at(kBoxCommands[I])(lmp);
}
const Input::CommandCreator kBoxWrappers[] = {&box_command_creator<0>, &box_command_creator<1>,
                                              &box_command_creator<2>};

// One category of the help: the names in columns of 16 characters (wider names take 32, 48 ...),
// at most 80 characters a line, the layout of LAMMPS's own style lists.
template <typename Entry, std::size_t N>
void print_category(std::FILE *out, const char *category, const Entry (&entries)[N])
{
  std::fprintf(out, "\n* %s styles (TAPMC)\n\n", category);
  int pos = 0;
  for (const auto &e : entries) {
    const int width = 16 * (static_cast<int>(std::strlen(e.name)) / 16 + 1);
    if (pos > 0 && pos + width > 80) {
      std::fprintf(out, "\n");
      pos = 0;
    }
    std::fprintf(out, "%-*s", width, e.name);
    pos += width;
  }
  std::fprintf(out, "\n");
}

}  // namespace

namespace tapmc {

void print_styles_help(std::FILE *out)
{
  // The commit of this binary: a campaign records it with every attempt (tapmc.campaign).
  std::fprintf(out, "TAPMC build: %s (git describe of the source tree it was built from)\n",
               TAPMC_BUILD_ID);
  std::fprintf(out, "TAPMC styles (registered by lmp_tapmc at start-up, not in the lists "
                    "above):\n");
  print_category(out, "Fix", kFixes);
  print_category(out, "Compute", kComputes);
  print_category(out, "Command", kCommands);
  std::fprintf(out, "\n");
  for (const auto &f : kFixes) std::fprintf(out, "  fix %-20s %s\n", f.name, f.info);
  for (const auto &c : kComputes) std::fprintf(out, "  compute %-16s %s\n", c.name, c.info);
  for (const auto &c : kCommands) std::fprintf(out, "  command %-16s %s\n", c.name, c.info);
  std::fprintf(out, "\n");
}

void register_styles(LAMMPS *lmp)
{
  insert_fix_and_compute_styles(lmp);
  auto &commands = *lmp->input->command_map;
  for (const auto &c : kCommands) commands[c.name] = c.creator;
  for (int i = 0; i < 3; ++i) {
    auto it = commands.find(kBoxCommands[i]);
    if (it == commands.end() || it->second == kBoxWrappers[i]) continue;
    original_box_creators()[kBoxCommands[i]] = it->second;
    it->second = kBoxWrappers[i];
  }
}

}  // namespace tapmc

extern "C" int tapmc_register(void *lmp)
{
  tapmc::register_styles(static_cast<LAMMPS *>(lmp));
  return 0;
}

// ---- PLUGIN interface (modern LAMMPS with PKG_PLUGIN) ----------------------------------------
// The layout below is LAMMPS's documented plugin ABI: a record per style handed to regfunc.
namespace {
typedef void *(plugin_factory_lmp)(void *);
typedef void *(plugin_factory_args)(void *, int, char **);
struct PluginRecord {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    plugin_factory_lmp *v1;
    plugin_factory_args *v2;
  } creator;
  void *handle;
};
typedef void (*plugin_regfunc)(PluginRecord *, void *);
}  // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = reinterpret_cast<plugin_regfunc>(regfunc);
  const char *version = static_cast<LAMMPS *>(lmp)->version;
  for (const auto &f : kFixes) {
    PluginRecord r{version, "fix", f.name, f.info, "TAPMC developers", {nullptr}, handle};
    r.creator.v2 = reinterpret_cast<plugin_factory_args *>(f.creator);
    reg(&r, lmp);
  }
  for (const auto &c : kComputes) {
    PluginRecord r{version, "compute", c.name, c.info, "TAPMC developers", {nullptr}, handle};
    r.creator.v2 = reinterpret_cast<plugin_factory_args *>(c.creator);
    reg(&r, lmp);
  }
  for (const auto &c : kCommands) {
    PluginRecord r{version, "command", c.name, c.info, "TAPMC developers", {nullptr}, handle};
    r.creator.v1 = reinterpret_cast<plugin_factory_lmp *>(c.creator);
    reg(&r, lmp);
  }
}
