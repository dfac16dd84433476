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
// They are dropped when the contact ends (no overlap). Between two evaluations of a contact the
// simulation time must move by one time step or not at all (Clock): a reset_timestep that moves it
// stops LAMMPS. A minimization is not time evolution: under minimize the internal variables do not
// advance in time (each evaluation responds to the change of overlap at zero elapsed time, the glassy
// response) and the contact keeps its time, which the run after the minimization resumes from. When a
// contact ends, the time steps per Hertz contact time of its largest overlap are measured
// (resolution()); fewer than MIN_STEPS_PER_CONTACT draw one warning per run (RunId).
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
  double ebar = 0.0;    // the modulus one step h_cache responds with: E_inf + sum_i w_i (Pa)

  int nterms() const { return static_cast<int>(e.size()); }
  double glassy() const;
  void cache(double h);
  void coefficients(double h, double *a_out, double *w_out) const;
};

// Stop LAMMPS (error->all, naming `who`) unless it runs on one MPI rank (the history is kept per
// rank and not migrated with the atoms) and the atoms have radii and IDs.
void require_one_rank_radii_ids(LAMMPS_NS::LAMMPS *lmp, const std::string &who);

// Stop LAMMPS (error->all, naming `who`) unless it runs in units si: the coefficients are in Pa and
// 1/s and the lengths in m, and LAMMPS does not convert a pair style's or a fix's own parameters.
void require_si_units(LAMMPS_NS::LAMMPS *lmp, const std::string &who);

// Stop LAMMPS (error->all, naming `who`) unless the time step is > 0 s: the internal variables relax
// over the elapsed time, which a step <= 0 s would run backwards or hold still.
void require_positive_time_step(LAMMPS_NS::LAMMPS *lmp, const std::string &who);

// A finite number (the whole text, as strtod reads it): true and out set, else false.
bool parse_number(const std::string &text, double &out);

// The simulation time (s) at the current time step (LAMMPS's atime, carried over changes of the step).
// During a minimization, LAMMPS's atime itself: the minimizer counts its iterations as time steps (and
// min_style fire changes update->dt), but the run after it starts again from atime (Integrate::init
// sets atimestep to the step without advancing atime), so no time passes in a minimization.
double simulation_time(LAMMPS_NS::LAMMPS *lmp);

// How the step and the time may have moved since a contact's last evaluation:
//   run:      by one time step (the step number by 1, the time by update->dt), or not at all;
//   setup:    not at all in time (a run's set-up, run 0: the step number changes only by reset_timestep,
//             which is consistent only when the time stays, i.e. reset_timestep N time $(time));
//   rerun:    forward by any time (rerun treats the time between two snapshots as one step);
//   minimize: a minimization (update->whichflag == 2, LAMMPS's "2 for min"; 1 is a run or rerun): the
//             step number moves by the minimizer's iterations and the time is not checked; the internal
//             variables do not advance in time and the contact keeps the time of its last state, so
//             the run that follows (whose set-up is at that time) continues from the contact's state.
enum class Clock { run, setup, rerun, minimize };
Clock clock_of(LAMMPS_NS::LAMMPS *lmp);

// One warning per run: a run as the force evaluations see it, LAMMPS's whichflag, firststep and
// laststep, which every run command (also with pre no, which skips init() and setup()), every chunk of
// run every and every minimize sets anew.
struct RunId {
  int which = -1;
  bigint first = -1, last = -1;
  bool operator==(const RunId &o) const { return which == o.which && first == o.first && last == o.last; }
  bool operator!=(const RunId &o) const { return !(*this == o); }
};
RunId run_of(LAMMPS_NS::LAMMPS *lmp);

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
  // start one evaluation of all contacts: the time step number, the simulation time (s), the
  // time step (s) and how they may have moved since the last evaluation; records not touched
  // before end() are dropped
  void begin(bigint step, double now, double dt, int maxterms, Clock clock);
  // E_inf u + sum_i q_i (Pa m^1.5) of the contact `key` at overlap power u = delta^1.5 (m^1.5),
  // its internal variables advanced from the state accepted at the previous step; reff (m) and
  // meff (kg), the contact's effective radius and mass, only measure how well the time step
  // resolves it (shortest below) and do not enter the force
  double advance(const Key &key, Law &law, double u, double reff, double meff);
  // drop the contacts not evaluated since begin()
  void end();
  void clear();
  std::size_t size() const { return recs.size(); }
  double memory_usage() const;

  // the first contact of this evaluation whose step or time moved otherwise than `clock` allows
  // (reset_timestep while it held history; a run with pre no right after a minimization, when
  // pre_no_after_minimize)
  struct Jump {
    bool set = false;
    bool pre_no_after_minimize = false;
    Key key{0, 0};
    bigint from_step = 0, to_step = 0;
    double from_time = 0.0, to_time = 0.0;    // s
  } jump;

  // among the contacts end() dropped, the one the time step resolved worst: n = t_H / dt, the
  // Hertz contact time of its largest overlap in time steps (Store::resolution), and the steps it
  // lasted; n is infinite when end() dropped none, and in a minimization (no time step to resolve)
  struct Ended {
    Key key{0, 0};
    double n = 0.0;
    bigint steps = 0;
    double overlap = 0.0;    // largest overlap over the effective radius
  } shortest;

 private:
  struct Rec {
    Key key;
    bigint step;     // the step of the current state
    double t_prev;   // time (s) of the state accepted at the previous step
    double t_cur;    // time (s) of the current state
    double u_prev;   // u at the accepted state
    double u_cur;    // u at the current state
    long call;       // the evaluation that last touched it
    bigint first;    // the step of first touch
    double u_max;    // the largest u (m^1.5)
    double stiff;    // 2 Ebar(dt) sqrt(reff) / meff (m^-1/2 s^-2): omega^2 = stiff sqrt(delta); < 0
                     // until measured (a contact that starts in a minimization, at its first step)
    double reff;     // m
    bool minimized;  // the last evaluation was in a minimization
  };
  void moved(const Rec &c);
  std::vector<Rec> recs;
  std::vector<double> q;    // per record: q_prev[stride], q_cur[stride]
  std::unordered_map<Key, std::size_t, KeyHash> index;
  std::vector<double> scratch_a, scratch_w;
  int stride = 0;
  long call = 0;
  bigint step = -1;
  double now = 0.0, dt = 0.0;
  Clock clock = Clock::run;
};

// The time-step rule's n = t_H / dt of a contact whose largest overlap delta (m) gives
// omega^2 = stiff sqrt(delta) (Store::Rec), for a time step dt (s).
double resolution(double stiff, double delta, double dt);

// One line for error->all: who, and the contact whose time moved (Store::jump; wall: a wall's key).
std::string jump_message(const std::string &who, const Store::Jump &jump, bool wall);
// One line for error->warning: who, and the contact the time step dt resolved worst (Store::shortest).
std::string resolution_message(const std::string &who, const Store::Ended &ended, double dt, bool wall);

// The deepest contact of one evaluation: its key and its overlap over its effective radius.
struct Deepest {
  Key key{0, 0};
  double overlap = 0.0;
  void note(const Key &k, double fraction)
  {
    if (fraction > overlap) {
      overlap = fraction;
      key = k;
    }
  }
};
// One line for error->warning: who, and the deepest contact of an evaluation past LARGE_OVERLAP.
std::string overlap_message(const std::string &who, const Deepest &deepest, bool wall);
// An overlap past this fraction of the effective radius draws one warning (the first time): Hertz contact
// holds for overlaps small against the radius (vcor flags s_max / r > 0.1 as large_indentation).
extern const double LARGE_OVERLAP;

// A contact resolved with fewer than this many time steps per Hertz contact time (n of the rule
// dt = t_H(Ebar(dt)) / n, measured by resolution() when a contact ends) draws one warning per run
// (vcor_hereditary.cpp says why this number).
extern const double MIN_STEPS_PER_CONTACT;

}    // namespace vcor

#endif
