// SPDX-License-Identifier: GPL-2.0-only
//
// vcor's hereditary Hertz contact for LAMMPS: the contact law and the per-contact internal
// variables shared by pair_style vcor/hereditary and fix vcor/wall/hereditary.
//
// The normal force of a contact with overlap delta (m) and reduced radius R (m) is
//
//     F = 4/3 sqrt(R) [E_inf u + sum_i q_i],   u = delta^(3/2),
//     q_i' = -beta_i q_i + E_i u',             q_i = 0 at first touch,
//
// clipped at zero (the bodies part where it returns to zero), with the contact's relaxation
// modulus E_c(t) = E_inf + sum_i E_i exp(-beta_i t) (Pa, rates in 1/s) as given to pair_coeff.
// Over a step of length h the update
//
//     q_i <- exp(-beta_i h) q_i + E_i (1 - exp(-beta_i h)) / (beta_i h) (u_new - u_old)
//
// is exact when u changes linearly over the step, and stable for any beta_i h.
//
// The internal variables of a contact are updated once per time step: a second evaluation at the
// same step (run setup, run 0, rerun) starts again from the state accepted at the previous step.
// They are dropped when the contact ends (no overlap).
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#ifndef VCOR_HEREDITARY_H
#define VCOR_HEREDITARY_H

#include "lmptype.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace vcor {

using LAMMPS_NS::bigint;
using LAMMPS_NS::tagint;

// The contact's relaxation modulus: a Prony series in the effective (plane-strain) contact form.
struct Law {
  double e_inf = 0.0;          // Pa
  std::vector<double> e;       // Pa
  std::vector<double> beta;    // 1/s
  bool set = false;

  // exponential step coefficients for the step h_cache: a_i = exp(-beta_i h),
  // w_i = E_i (1 - a_i) / (beta_i h)
  double h_cache = -1.0;
  std::vector<double> a, w;

  int nterms() const { return static_cast<int>(e.size()); }
  double glassy() const;
  void cache(double h);
  void coefficients(double h, double *a_out, double *w_out) const;
};

// Stop LAMMPS (error->all, naming `who`) unless it runs on one MPI rank (the history is kept per
// rank and not migrated with the atoms) and the atoms have radii and IDs.
void require_one_rank_radii_ids(LAMMPS_NS::LAMMPS *lmp, const std::string &who);

// The simulation time (s) at the current time step (LAMMPS's atime, carried over changes of the step).
double simulation_time(LAMMPS_NS::LAMMPS *lmp);

// Parse "E_inf [E_1 beta_1 ...]": returns "" and fills law, or a one-line message naming the
// coefficient that is wrong.
std::string parse_law(const std::vector<std::string> &args, Law &law);

// A contact: two atom IDs (a pair, a < b) or one atom ID and a wall side.
struct Key {
  tagint a, b;
  bool operator==(const Key &o) const { return a == o.a && b == o.b; }
};

struct KeyHash {
  std::size_t operator()(const Key &k) const
  {
    const std::uint64_t x = static_cast<std::uint64_t>(k.a) * 0x9E3779B97F4A7C15ULL;
    return static_cast<std::size_t>(x ^ (static_cast<std::uint64_t>(k.b) + 0x7F4A7C159E3779B9ULL + (x << 6) +
                                         (x >> 2)));
  }
};

// The internal variables of every touching contact, keyed by atom IDs.
class Store {
 public:
  // start one evaluation of all contacts: the time step number, the simulation time (s) and the
  // time step (s); records not touched before end() are dropped
  void begin(bigint step, double now, double dt, int maxterms);
  // E_inf u + sum_i q_i (Pa m^1.5) of the contact `key` at overlap power u = delta^1.5 (m^1.5),
  // its internal variables advanced from the state accepted at the previous step
  double advance(const Key &key, Law &law, double u);
  // drop the contacts not evaluated since begin()
  void end();
  void clear();
  std::size_t size() const { return recs.size(); }
  double memory_usage() const;
  // set when the simulation time went back while contacts held history (reset_timestep)
  bool backwards = false;

 private:
  struct Rec {
    Key key;
    bigint step;     // the step of the current state
    double t_prev;   // time (s) of the state accepted at the previous step
    double t_cur;    // time (s) of the current state
    double u_prev;   // u at the accepted state
    double u_cur;    // u at the current state
    long call;       // the evaluation that last touched it
  };
  std::vector<Rec> recs;
  std::vector<double> q;    // per record: q_prev[stride], q_cur[stride]
  std::unordered_map<Key, std::size_t, KeyHash> index;
  std::vector<double> scratch_a, scratch_w;
  int stride = 0;
  long call = 0;
  bigint step = -1;
  double now = 0.0, dt = 0.0;
};

}    // namespace vcor

#endif
