// SPDX-License-Identifier: GPL-2.0-only
//
// pair_style vcor/hereditary (pair_vcor_hereditary.h, vcor_hereditary.h).
//
//   pair_style vcor/hereditary
//   pair_coeff I J E_inf [E_1 beta_1 E_2 beta_2 ...]
//
// The coefficients are the contact's relaxation modulus E_c(t) = E_inf + sum_i E_i exp(-beta_i t)
// in Pa and 1/s, in the effective plane-strain form: for two spheres of one material of Young's
// relaxation modulus E(t) and Poisson ratio nu, E_c = E / (2 (1 - nu^2)). The force between
// spheres i and j with overlap delta is 4/3 sqrt(R) (E_inf u + sum_i q_i), u = delta^1.5,
// R = r_i r_j / (r_i + r_j), clipped at zero; no tangential force, no potential energy. Units si
// only, with a time step > 0 s: init_style() refuses another unit style (the coefficients are not
// converted) and a time step <= 0 s.
// compute pair vcor/hereditary gives two numbers: [1] the contacts evaluated in the last force
// evaluation, [2] the smallest n of the time-step rule (Store::shortest) among the contacts that have
// ended since the pair style was defined (inf while none has).
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#include "pair_vcor_hereditary.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

using namespace LAMMPS_NS;

PairVcorHereditary::PairVcorHereditary(LAMMPS *lmp) :
    Pair(lmp), ncontacts(0.0), nmin(std::numeric_limits<double>::infinity()), maxterms(0), stride(0)
{
  single_enable = 0;
  nextra = 2;
  pvector = new double[nextra];
  pvector[0] = 0.0;
  pvector[1] = nmin;
  restartinfo = 0;
  writedata = 0;
  finitecutflag = 1;
  one_coeff = 0;
}

PairVcorHereditary::~PairVcorHereditary()
{
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
  delete[] pvector;
}

void PairVcorHereditary::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) setflag[i][j] = 0;
  stride = n + 1;
  laws.assign((n + 1) * (n + 1), vcor::Law());
  maxrad.assign(n + 1, 0.0);
}

void PairVcorHereditary::settings(int narg, char **arg)
{
  if (narg != 0)
    error->all(FLERR, "pair_style vcor/hereditary takes no arguments, got '{}' (the law is set by pair_coeff)",
               arg[0]);
}

void PairVcorHereditary::coeff(int narg, char **arg)
{
  if (narg < 2) error->all(FLERR, "pair_coeff vcor/hereditary: I J E_inf [E_1 beta_1 ...]");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  std::vector<std::string> values(arg + 2, arg + narg);
  vcor::Law parsed;
  const std::string why = vcor::parse_law(values, parsed);
  if (!why.empty()) error->all(FLERR, "pair_coeff {} {} vcor/hereditary: {}", arg[0], arg[1], why);
  int count = 0;
  for (int i = ilo; i <= ihi; ++i)
    for (int j = std::max(jlo, i); j <= jhi; ++j) {
      law(i, j) = parsed;
      law(j, i) = parsed;
      setflag[i][j] = 1;
      ++count;
    }
  if (count == 0) error->all(FLERR, "pair_coeff {} {} vcor/hereditary: no type pair matched", arg[0], arg[1]);
}

void PairVcorHereditary::init_style()
{
  vcor::require_si_units(lmp, "pair_style vcor/hereditary");
  vcor::require_positive_time_step(lmp, "pair_style vcor/hereditary");
  vcor::require_one_rank_radii_ids(lmp, "pair_style vcor/hereditary");

  neighbor->add_request(this, NeighConst::REQ_SIZE);

  // largest radius per type: atoms present now and those fix pour / deposit will insert
  const int ntypes = atom->ntypes;
  std::vector<double> local(ntypes + 1, 0.0);
  for (const char *style : {"^pour", "^deposit"})
    for (Fix *fix : modify->get_fix_by_style(style))
      for (int t = 1; t <= ntypes; ++t) {
        int itype = t;
        auto *r = static_cast<double *>(fix->extract("radius", itype));
        if (r) local[t] = std::max(local[t], *r);
      }
  for (int i = 0; i < atom->nlocal; ++i) local[atom->type[i]] = std::max(local[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(local.data(), maxrad.data(), ntypes + 1, MPI_DOUBLE, MPI_MAX, world);

  // one history per pair of atom IDs: two periodic images of one atom must not both touch another
  const double rmax = *std::max_element(maxrad.begin(), maxrad.end());
  for (int d = 0; d < domain->dimension; ++d)
    if (domain->periodicity[d] && domain->prd[d] < 4.0 * rmax)
      error->all(FLERR,
                 "pair_style vcor/hereditary: the periodic box length {} m in dimension {} is shorter than "
                 "four times the largest radius ({} m): a sphere could touch two images of another, whose "
                 "contacts would share one history",
                 domain->prd[d], "xyz"[d], rmax);

  maxterms = 0;
  for (int i = 1; i <= ntypes; ++i)
    for (int j = 1; j <= ntypes; ++j)
      if (law(i, j).set) maxterms = std::max(maxterms, law(i, j).nterms());
}

double PairVcorHereditary::init_one(int i, int j)
{
  if (setflag[i][j] == 0)
    error->all(FLERR,
               "pair_coeff {} {} is not set: vcor/hereditary does not mix the series of two types (give the "
               "contact's own relaxation modulus for this type pair)",
               i, j);
  return maxrad[i] + maxrad[j];
}

void PairVcorHereditary::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  double **x = atom->x;
  double **f = atom->f;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  double *mass = atom->mass;
  tagint *tag = atom->tag;
  int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;

  const int inum = list->inum;
  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  // before the history: a step <= 0 s would otherwise show as a jump of the time (jump_message)
  vcor::require_positive_time_step(lmp, "pair_style vcor/hereditary");
  store.begin(update->ntimestep, vcor::simulation_time(lmp), update->dt, maxterms, vcor::clock_of(lmp));
  long touching = 0;
  vcor::Deepest deepest;

  for (int ii = 0; ii < inum; ++ii) {
    const int i = ilist[ii];
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double radi = radius[i];
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];

    for (int jj = 0; jj < jnum; ++jj) {
      const int j = jlist[jj] & NEIGHMASK;
      const double delx = xi - x[j][0];
      const double dely = yi - x[j][1];
      const double delz = zi - x[j][2];
      const double rsq = delx * delx + dely * dely + delz * delz;
      const double radsum = radi + radius[j];
      if (rsq >= radsum * radsum) continue;

      const double r = std::sqrt(rsq);
      if (r == 0.0) error->one(FLERR, "pair_style vcor/hereditary: atoms {} and {} at the same position", tag[i],
                               tag[j]);
      const double delta = radsum - r;
      const double u = delta * std::sqrt(delta);
      const vcor::Key key = tag[i] < tag[j] ? vcor::Key{tag[i], tag[j]} : vcor::Key{tag[j], tag[i]};
      const double reff = radi * radius[j] / radsum;
      deepest.note(key, delta / reff);
      const double mi = rmass ? rmass[i] : (mass ? mass[itype] : 0.0);
      const double mj = rmass ? rmass[j] : (mass ? mass[type[j]] : 0.0);
      // the reduced mass measures the time-step rule's n (Store::advance). With one of the two atoms
      // held still (fix setforce 0, fix freeze) the contact moves the other's mass m_moving alone,
      // and n is underestimated by sqrt(1 + m_moving / m_held): sqrt(2) for equal masses, more when
      // the held atom is the lighter. The warning then errs early (on the safe side), never late.
      const double g = store.advance(key, law(itype, type[j]), u, reff, mi * mj / (mi + mj));
      ++touching;
      if (g <= 0.0) continue;    // the force is clipped at zero: the bodies have parted

      const double fn = 4.0 / 3.0 * std::sqrt(reff) * g;
      const double fpair = fn / r;
      f[i][0] += delx * fpair;
      f[i][1] += dely * fpair;
      f[i][2] += delz * fpair;
      if (newton_pair || j < nlocal) {
        f[j][0] -= delx * fpair;
        f[j][1] -= dely * fpair;
        f[j][2] -= delz * fpair;
      }
      if (evflag) ev_tally(i, j, nlocal, newton_pair, 0.0, 0.0, fpair, delx, dely, delz);
    }
  }
  store.end();
  ncontacts = static_cast<double>(touching);
  nmin = std::min(nmin, store.shortest.n);
  pvector[0] = ncontacts;
  pvector[1] = nmin;
  if (store.jump.set)
    error->all(FLERR, vcor::jump_message("pair_style vcor/hereditary", store.jump, false));
  if (store.shortest.n < vcor::MIN_STEPS_PER_CONTACT && vcor::run_of(lmp) != warned) {
    warned = vcor::run_of(lmp);
    if (comm->me == 0)
      error->warning(FLERR, vcor::resolution_message("pair_style vcor/hereditary", store.shortest, update->dt, false));
  }

  if (deepest.overlap > vcor::LARGE_OVERLAP && !warned_overlap) {
    warned_overlap = true;
    if (comm->me == 0) error->warning(FLERR, vcor::overlap_message("pair_style vcor/hereditary", deepest, false));
  }

  if (vflag_fdotr) virial_fdotr_compute();
}

void *PairVcorHereditary::extract(const char *name, int &dim)
{
  dim = 0;
  if (std::string(name) == "ncontacts") return &ncontacts;
  return nullptr;
}

double PairVcorHereditary::memory_usage()
{
  return Pair::memory_usage() + store.memory_usage();
}
