// SPDX-License-Identifier: GPL-2.0-only
//
// vcor's hereditary Hertz contact for LAMMPS: the contact law (parsing, exponential step
// coefficients) and the store of per-contact internal variables (vcor_hereditary.h).
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#include "vcor_hereditary.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "input.h"
#include "lammps.h"
#include "update.h"

#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

namespace vcor {

double Law::glassy() const
{
  double g = e_inf;
  for (double x : e) g += x;
  return g;
}

void Law::coefficients(double h, double *a_out, double *w_out) const
{
  for (int i = 0; i < nterms(); ++i) {
    const double x = beta[i] * h;
    a_out[i] = std::exp(-x);
    // (1 - exp(-x)) / x, with its limit 1 at x = 0
    w_out[i] = e[i] * (x > 0.0 ? -std::expm1(-x) / x : 1.0);
  }
}

void Law::cache(double h)
{
  if (h == h_cache) return;
  a.resize(e.size());
  w.resize(e.size());
  coefficients(h, a.data(), w.data());
  ebar = e_inf;
  for (double x : w) ebar += x;
  h_cache = h;
}

static std::string show(double x)
{
  std::ostringstream s;
  s.precision(12);
  s << x;
  return s.str();
}

bool parse_number(const std::string &text, double &out)
{
  if (text.empty()) return false;
  const char *start = text.c_str();
  char *end = nullptr;
  errno = 0;
  out = std::strtod(start, &end);
  return errno == 0 && end != start && *end == '\0' && std::isfinite(out);
}

std::string parse_law(const std::vector<std::string> &args, Law &law)
{
  if (args.empty())
    return "needs the contact's relaxation modulus: E_inf (Pa), then pairs E_i (Pa) beta_i (1/s)";
  const std::size_t nprony = args.size() - 1;
  if (nprony % 2 != 0)
    return "the Prony numbers after E_inf come in pairs E_i beta_i: got " + std::to_string(nprony) +
        (nprony == 1 ? " number" : " numbers") + " after E_inf (an odd count: E_" + std::to_string(nprony / 2 + 1) +
        " has no beta_" +
        std::to_string(nprony / 2 + 1) + ")";
  Law out;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const bool is_beta = k > 0 && k % 2 == 0;
    const std::string name = k == 0 ? "E_inf" : (is_beta ? "beta_" : "E_") + std::to_string((k + 1) / 2);
    const std::string unit = is_beta ? "1/s" : "Pa";
    double x = 0.0;
    if (!parse_number(args[k], x))
      return name + " = '" + args[k] + "' is not a finite number (" + unit + ")";
    if (is_beta) {
      if (x <= 0.0)
        return name + " = " + show(x) + " 1/s must be > 0 1/s (a term that does not relax belongs in E_inf)";
      out.beta.push_back(x);
    } else {
      if (x < 0.0)
        return name + " = " + show(x) + " Pa is negative: a modulus must be >= 0 Pa";
      if (k == 0)
        out.e_inf = x;
      else
        out.e.push_back(x);
    }
  }
  if (!(out.glassy() > 0.0))
    return "E_inf + sum E_i = " + show(out.glassy()) + " Pa: the contact needs a modulus > 0 Pa";
  out.set = true;
  law = out;
  return "";
}

void require_one_rank_radii_ids(LAMMPS_NS::LAMMPS *lmp, const std::string &who)
{
  if (lmp->comm->nprocs > 1)
    lmp->error->all(FLERR,
                    "{} runs on one MPI rank: its contact history is kept per rank and not migrated with the "
                    "atoms, so {} ranks would lose it (run with 1 rank)",
                    who, lmp->comm->nprocs);
  if (!lmp->atom->radius_flag) lmp->error->all(FLERR, "{} needs atom radii (atom_style sphere)", who);
  if (!lmp->atom->tag_enable) lmp->error->all(FLERR, "{} needs atom IDs (atom_modify id yes)", who);
}

void require_si_units(LAMMPS_NS::LAMMPS *lmp, const std::string &who)
{
  const char *style = lmp->update->unit_style;
  if (!style || std::strcmp(style, "si") != 0)
    lmp->error->all(FLERR,
                    "{}: the run has units {}, but the coefficients are in Pa and 1/s and the lengths in m: use "
                    "units si",
                    who, style ? style : "(none)");
}

void require_positive_time_step(LAMMPS_NS::LAMMPS *lmp, const std::string &who)
{
  const double dt = lmp->update->dt;
  if (!(dt > 0.0)) lmp->error->all(FLERR, "{}: the time step must be > 0 s, got {} s (timestep)", who, dt);
}

// Update::whichflag: 0 unset, 1 dynamics (run, rerun), 2 minimization (update.h)
static constexpr int WHICH_MINIMIZE = 2;

double simulation_time(LAMMPS_NS::LAMMPS *lmp)
{
  const LAMMPS_NS::Update *update = lmp->update;
  if (update->whichflag == WHICH_MINIMIZE) return update->atime;
  return update->atime + static_cast<double>(update->ntimestep - update->atimestep) * update->dt;
}

Clock clock_of(LAMMPS_NS::LAMMPS *lmp)
{
  if (lmp->update->whichflag == WHICH_MINIMIZE) return Clock::minimize;
  // rerun evaluates the forces of each snapshot in a set-up, after moving the step and the time on
  const char *command = lmp->input ? lmp->input->command : nullptr;
  if (command && std::strcmp(command, "rerun") == 0) return Clock::rerun;
  return lmp->update->setupflag ? Clock::setup : Clock::run;
}

RunId run_of(LAMMPS_NS::LAMMPS *lmp)
{
  const LAMMPS_NS::Update *update = lmp->update;
  RunId id;
  id.which = update->whichflag;
  id.first = update->firststep;
  id.last = update->laststep;
  return id;
}

// Two times of a contact count as one when they differ by at most TIME_SLACK time steps plus the
// round-off of LAMMPS's atime + (ntimestep - atimestep) dt (a few ulps of the time itself): a
// relaxation over 1e-6 of a step is far below the step's own error, and a time written back with
// reset_timestep N time $(time) (15 or more digits) is well within it.
static constexpr double TIME_SLACK = 1e-6;

static double slack(double now, double dt)
{
  return TIME_SLACK * dt + 64.0 * DBL_EPSILON * std::fabs(now);
}

// t_H omega_max of an elastic Hertz collision (m delta'' = -K delta^1.5): with the deck's contact time
// t_H = 3.2181 (m/K)^(2/5) v^(-1/5) and omega_max^2 = (3/2) K sqrt(delta_max) / m at the largest overlap
// delta_max = (5 m v^2 / (4 K))^(2/5), t_H omega_max = 3.2181 sqrt(1.5 * 1.25^0.2) = 4.0303 for any m, K, v.
static const double HERTZ_TIME_OMEGA = 3.2180654597185065 * std::sqrt(1.5 * std::pow(1.25, 0.2));

double resolution(double stiff, double delta, double dt)
{
  const double omega = std::sqrt(stiff * std::sqrt(delta));
  return omega > 0.0 ? HERTZ_TIME_OMEGA / (omega * dt) : std::numeric_limits<double>::infinity();
}

// Why 10. resolution() gives the n of the time-step rule: in the deck in.hereditary (-var nsteps n,
// the sls pair at 1 m/s, two spheres or a sphere on a wall) it measures n within 1% from n = 3 up
// (3.01 at 3, 5.02 at 5, 9.95 at 10), and 1.8 at 2. There the COR is vcor's within 2e-4 at n = 30, off
// by 3e-3 at n = 10 (more than the 2e-3 the deck is checked to), 3e-2 at n = 5, 0.08 at n = 3, and above
// 1 (energy created: the step's omega dt = 4.03 / n passes Verlet's limit 2) at n = 2: the test
// test_a_time_step_too_large_for_the_rule_warns_once (tests/dem/test_lammps_plugin.py) prints these.
// examples/in.packing (1e-5 s) resolves every contact that ends in its 1e5 steps with n >= 27 between
// spheres and n >= 24.8 with the floor (printed by test_a_packing_of_500_spheres_settles_under_gravity);
// a light touch (an overlap of 1e-6 of the radius, over a step or two) has a large n, so it does not
// warn however few steps it lasts.
const double MIN_STEPS_PER_CONTACT = 10.0;

// the contact as a reader knows it: two atom IDs, or an atom ID and a wall (Key{tag, side})
static std::string contact_text(const Key &key, bool wall)
{
  if (wall) return "atom " + std::to_string(key.a) + " on the " + (key.b == 0 ? "lower" : "upper") + " wall";
  return "atoms " + std::to_string(key.a) + " and " + std::to_string(key.b);
}

// vcor's own bound (vcor.solvers.validity: s_max / r > 0.1 is large_indentation)
const double LARGE_OVERLAP = 0.1;

std::string overlap_message(const std::string &who, const Deepest &deepest, bool wall)
{
  std::ostringstream s;
  s.precision(3);
  s << who << ": an overlap of " << deepest.overlap << " of the effective radius (" << contact_text(deepest.key, wall)
    << "), above " << LARGE_OVERLAP << ": Hertz contact holds for overlaps small against the radius. Moduli "
    << "written in MPa or kPa instead of Pa give this (units si: E_inf and E_i in Pa, beta_i in 1/s); so do "
    << "speeds beyond the material's range (warned once)";
  return s.str();
}

std::string jump_message(const std::string &who, const Store::Jump &jump, bool wall)
{
  std::ostringstream s;
  s.precision(12);
  s << who << ": the simulation time went from " << jump.from_time << " s at step " << jump.from_step << " to "
    << jump.to_time << " s at step " << jump.to_step << " between two evaluations of a contact ("
    << contact_text(jump.key, wall) << "), which is not one time step: ";
  if (jump.pre_no_after_minimize)
    s << "a run with pre no right after a minimization counts the minimizer's iterations as time steps and the "
         "contact's internal variables would take that as elapsed time. Run with pre yes (the default) after "
         "minimize";
  else
    s << "reset_timestep moves the time with the step (forward by the steps skipped, back to 0) and the contact's "
         "internal variables would take that as elapsed time. Reset the step while no contact touches, or keep the "
         "time: reset_timestep N time $(time)";
  return s.str();
}

std::string resolution_message(const std::string &who, const Store::Ended &ended, double dt, bool wall)
{
  std::ostringstream s;
  s.precision(3);
  s << who << ": the time step " << dt << " s resolves a contact with n = " << ended.n
    << " steps per Hertz contact time (" << contact_text(ended.key, wall) << ": it lasted " << ended.steps
    << (ended.steps == 1 ? " step" : " steps") << ", its largest overlap " << ended.overlap
    << " of the effective radius); the time-step rule dt = t_H(Ebar(dt))/n needs n >= " << MIN_STEPS_PER_CONTACT
    << " for a rebound to be trusted (below n = 2 the step is unstable and creates energy): reduce the time step "
       "(warned once per run)";
  return s.str();
}

void Store::begin(bigint step_, double now_, double dt_, int maxterms, Clock clock_)
{
  ++call;
  step = step_;
  now = now_;
  dt = dt_;
  clock = clock_;
  jump = Jump();
  shortest = Ended();
  shortest.n = std::numeric_limits<double>::infinity();
  if (maxterms > stride) {
    std::vector<double> grown(recs.size() * 2 * maxterms, 0.0);
    for (std::size_t r = 0; r < recs.size(); ++r)
      for (int half = 0; half < 2; ++half)
        for (int i = 0; i < stride; ++i)
          grown[(2 * r + half) * maxterms + i] = q[(2 * r + half) * stride + i];
    q.swap(grown);
    stride = maxterms;
  }
  scratch_a.resize(stride);
  scratch_w.resize(stride);
}

void Store::moved(const Rec &c)
{
  if (jump.set) return;
  jump.set = true;
  // a run's first step without a set-up (pre no) after a minimization: LAMMPS's time then counts the
  // minimizer's iterations as time steps (the set-up's Integrate::init would start from atime again)
  jump.pre_no_after_minimize = c.minimized && clock == Clock::run;
  jump.key = c.key;
  jump.from_step = c.step;
  jump.to_step = step;
  jump.from_time = c.t_cur;
  jump.to_time = now;
}

double Store::advance(const Key &key, Law &law, double u, double reff, double meff)
{
  const bool minimizing = clock == Clock::minimize;
  std::size_t r;
  auto found = index.find(key);
  if (found == index.end()) {
    // first touch: the internal variables start at zero, one step ago, with u = 0 (in a minimization,
    // at the same time: no time passes)
    r = recs.size();
    recs.push_back({key, step, minimizing ? now : now - dt, now, 0.0, 0.0, call, step, 0.0, -1.0, reff, minimizing});
    q.resize((r + 1) * 2 * stride, 0.0);
    index.emplace(key, r);
  } else if (minimizing) {
    // a minimizer's iteration: the last state becomes the accepted one at the same time (the contact's
    // time does not move, and is not checked)
    r = found->second;
    Rec &c = recs[r];
    if (c.step != step) {
      double *qp = &q[2 * r * stride];
      for (int i = 0; i < stride; ++i) qp[i] = qp[stride + i];
      c.t_prev = c.t_cur;
      c.u_prev = c.u_cur;
      c.step = step;
    }
  } else {
    r = found->second;
    Rec &c = recs[r];
    const double tol = slack(now, dt);
    if (c.step != step) {
      // a new step: by one time step in a run; with the time kept at a set-up (reset_timestep N
      // time T with T the time of the last step); forward in a rerun
      const double h = now - c.t_cur;
      const bool ok = clock == Clock::run     ? step == c.step + 1 && std::fabs(h - dt) <= tol
                      : clock == Clock::setup ? std::fabs(h) <= tol
                                              : h >= -tol;
      if (!ok) moved(c);
      // the state of the last one becomes the accepted previous state
      double *qp = &q[2 * r * stride];
      for (int i = 0; i < stride; ++i) qp[i] = qp[stride + i];
      c.t_prev = c.t_cur;
      c.u_prev = c.u_cur;
      c.step = step;
    } else if (std::fabs(now - c.t_cur) > tol) {
      moved(c);    // the same step at another time (reset_timestep N time T to the step it is at)
    }
  }
  Rec &c = recs[r];
  if (c.stiff < 0.0 && !minimizing) {
    // the contact's stiffness for resolution(), at the time step it is integrated with; meff is the
    // caller's (the pair style's reduced mass errs early with one atom held still: pair_vcor_hereditary.cpp)
    law.cache(dt);
    c.stiff = meff > 0.0 ? 2.0 * law.ebar * std::sqrt(reff) / meff : 0.0;    // 0: not measured
  }
  // the time since the accepted state: in a minimization the contact's own (0 after its first
  // iteration; at the step a run ended, that step's length, which gives the run's last state again)
  const double t = minimizing ? c.t_cur : now;
  double h = t - c.t_prev;
  if (h < 0.0) h = 0.0;    // within the slack (else the jump stops LAMMPS after this evaluation)
  const double *a, *w;
  if (std::fabs(h - dt) <= 1e-9 * dt) {
    law.cache(dt);
    a = law.a.data();
    w = law.w.data();
  } else {
    law.coefficients(h, scratch_a.data(), scratch_w.data());
    a = scratch_a.data();
    w = scratch_w.data();
  }
  const double *qp = &q[2 * r * stride];
  double *qc = &q[(2 * r + 1) * stride];
  const double du = u - c.u_prev;
  double sum = 0.0;
  const int n = law.nterms();
  for (int i = 0; i < n; ++i) {
    qc[i] = a[i] * qp[i] + w[i] * du;
    sum += qc[i];
  }
  c.u_cur = u;
  c.t_cur = t;
  c.call = call;
  c.minimized = minimizing;
  if (u > c.u_max) c.u_max = u;
  return law.e_inf * u + sum;
}

void Store::end()
{
  std::size_t r = 0;
  while (r < recs.size()) {
    if (recs[r].call == call) {
      ++r;
      continue;
    }
    // the contact has ended: how well did the time step resolve it? (not in a minimization: no time
    // step resolves it there)
    const Rec &c = recs[r];
    if (clock != Clock::minimize && c.stiff >= 0.0) {
      const double delta = std::cbrt(c.u_max * c.u_max);
      const double n = resolution(c.stiff, delta, dt);
      if (n < shortest.n) shortest = {c.key, n, c.step - c.first + 1, delta / c.reff};
    }
    index.erase(recs[r].key);
    const std::size_t last = recs.size() - 1;
    if (r != last) {
      recs[r] = recs[last];
      for (int i = 0; i < 2 * stride; ++i) q[2 * r * stride + i] = q[2 * last * stride + i];
      index[recs[r].key] = r;
    }
    recs.pop_back();
    q.resize(recs.size() * 2 * stride);
  }
}

void Store::clear()
{
  recs.clear();
  q.clear();
  index.clear();
}

double Store::memory_usage() const
{
  return static_cast<double>(recs.capacity() * sizeof(Rec) + q.capacity() * sizeof(double) +
                             index.size() * (sizeof(Key) + sizeof(std::size_t) + 2 * sizeof(void *)));
}

}    // namespace vcor
