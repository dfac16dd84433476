// SPDX-License-Identifier: GPL-2.0-only
//
// fix vcor/wall/hereditary (fix_vcor_wall_hereditary.h, vcor_hereditary.h).
//
//   fix ID group vcor/wall/hereditary xplane|yplane|zplane lo hi E_inf [E_1 beta_1 ...]
//
// lo, hi: the walls' positions (m) or NULL. A sphere of radius r at distance d from a wall
// overlaps it by delta = r - d; the force is 4/3 sqrt(r) (E_inf u + sum_i q_i), u = delta^1.5,
// clipped at zero, along the wall's normal. The coefficients are the contact's relaxation
// modulus in the effective plane-strain form: for a sphere of Young's relaxation modulus E(t)
// and Poisson ratio nu on a rigid wall, E_c = E / (1 - nu^2). The global vector holds the force
// of the walls on the group (N, 3 components), the number of touching contacts and the smallest n
// of the time-step rule (Store::shortest) among the contacts that have ended since the fix was
// defined (inf while none has). The walls act in a minimization too (as the pair style does), where
// the contact does not advance in time (vcor_hereditary.h). Units si only, with a time step > 0 s
// (init() refuses another unit style and a time step <= 0 s).
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#include "fix_vcor_wall_hereditary.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

FixVcorWallHereditary::FixVcorWallHereditary(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dim(0), has_lo(false), has_hi(false), lo(0.0), hi(0.0), wall_force{0.0, 0.0, 0.0},
    ncontacts(0.0), nmin(std::numeric_limits<double>::infinity())
{
  const std::string usage = "fix ID group vcor/wall/hereditary xplane|yplane|zplane lo hi E_inf [E_1 beta_1 ...]";
  if (narg < 7) error->all(FLERR, "fix vcor/wall/hereditary: too few arguments; {}", usage);
  const std::string style = arg[3];
  if (style == "xplane")
    dim = 0;
  else if (style == "yplane")
    dim = 1;
  else if (style == "zplane")
    dim = 2;
  else
    error->all(FLERR, "fix vcor/wall/hereditary: wall style '{}' is not xplane, yplane or zplane; {}", style, usage);
  for (int k = 0; k < 2; ++k) {
    const char *text = arg[4 + k];
    if (std::strcmp(text, "NULL") == 0) continue;
    double &where = k == 0 ? lo : hi;
    if (!vcor::parse_number(text, where))
      error->all(FLERR, "fix vcor/wall/hereditary: {} = '{}' is not a finite number (m) or NULL; {}",
                 k == 0 ? "lo" : "hi", text, usage);
    (k == 0 ? has_lo : has_hi) = true;
  }
  if (!has_lo && !has_hi) error->all(FLERR, "fix vcor/wall/hereditary: both walls are NULL; {}", usage);
  if (has_lo && has_hi && lo >= hi)
    error->all(FLERR, "fix vcor/wall/hereditary: the lower wall ({} m) must be below the upper wall ({} m)", lo,
               hi);
  std::vector<std::string> values(arg + 6, arg + narg);
  const std::string why = vcor::parse_law(values, law);
  if (!why.empty()) {
    // a forgotten lo or hi (NULL) shifts every number after it by one, and the count comes out odd
    const std::string shifted = why.find("odd count") == std::string::npos
        ? std::string()
        : std::string("; lo and hi were read as ") + arg[4] + " and " + arg[5] +
            " (m): if one of them is missing, write NULL for it";
    error->all(FLERR, "fix {} vcor/wall/hereditary: {}{}", id, why, shifted);
  }
  if (domain->periodicity[dim])
    error->all(FLERR, "fix vcor/wall/hereditary: a wall across the periodic dimension {}", "xyz"[dim]);

  vector_flag = 1;
  size_vector = 5;
  global_freq = 1;
  extvector = -1;
  extlist = new int[size_vector]{1, 1, 1, 1, 0};
}

FixVcorWallHereditary::~FixVcorWallHereditary()
{
  delete[] extlist;
}

int FixVcorWallHereditary::setmask()
{
  return POST_FORCE | MIN_POST_FORCE;
}

void FixVcorWallHereditary::init()
{
  vcor::require_si_units(lmp, "fix vcor/wall/hereditary");
  vcor::require_positive_time_step(lmp, "fix vcor/wall/hereditary");
  vcor::require_one_rank_radii_ids(lmp, "fix vcor/wall/hereditary");
}

void FixVcorWallHereditary::setup(int vflag)
{
  post_force(vflag);
}

void FixVcorWallHereditary::min_setup(int vflag)
{
  post_force(vflag);
}

void FixVcorWallHereditary::min_post_force(int vflag)
{
  post_force(vflag);
}

void FixVcorWallHereditary::post_force(int /*vflag*/)
{
  double **x = atom->x;
  double **f = atom->f;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  double *mass = atom->mass;
  int *type = atom->type;
  tagint *tag = atom->tag;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  // before the history: a step <= 0 s would otherwise show as a jump of the time (jump_message)
  vcor::require_positive_time_step(lmp, "fix vcor/wall/hereditary");
  store.begin(update->ntimestep, vcor::simulation_time(lmp), update->dt, law.nterms(), vcor::clock_of(lmp));
  wall_force[0] = wall_force[1] = wall_force[2] = 0.0;
  double contacts = 0.0;
  vcor::Deepest deepest;
  for (int i = 0; i < nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    for (int side = 0; side < 2; ++side) {
      if ((side == 0 && !has_lo) || (side == 1 && !has_hi)) continue;
      const double gap = side == 0 ? x[i][dim] - lo : hi - x[i][dim];
      const double delta = radius[i] - gap;
      if (delta <= 0.0) continue;
      const double u = delta * std::sqrt(delta);
      const double mi = rmass ? rmass[i] : (mass ? mass[type[i]] : 0.0);    // the wall does not move
      deepest.note(vcor::Key{tag[i], side}, delta / radius[i]);
      const double g = store.advance(vcor::Key{tag[i], side}, law, u, radius[i], mi);
      contacts += 1.0;
      if (g <= 0.0) continue;    // clipped at zero: the sphere has left the wall
      const double fn = 4.0 / 3.0 * std::sqrt(radius[i]) * g;
      const double signed_fn = side == 0 ? fn : -fn;
      f[i][dim] += signed_fn;
      wall_force[dim] += signed_fn;
    }
  }
  store.end();
  ncontacts = contacts;
  nmin = std::min(nmin, store.shortest.n);
  if (store.jump.set) error->all(FLERR, vcor::jump_message("fix vcor/wall/hereditary", store.jump, true));
  if (store.shortest.n < vcor::MIN_STEPS_PER_CONTACT && vcor::run_of(lmp) != warned) {
    warned = vcor::run_of(lmp);
    if (comm->me == 0)
      error->warning(FLERR, vcor::resolution_message("fix vcor/wall/hereditary", store.shortest, update->dt, true));
  }
  if (deepest.overlap > vcor::LARGE_OVERLAP && !warned_overlap) {
    warned_overlap = true;
    if (comm->me == 0) error->warning(FLERR, vcor::overlap_message("fix vcor/wall/hereditary", deepest, true));
  }
}

double FixVcorWallHereditary::compute_vector(int n)
{
  return n < 3 ? wall_force[n] : (n == 3 ? ncontacts : nmin);
}

double FixVcorWallHereditary::memory_usage()
{
  return store.memory_usage();
}
