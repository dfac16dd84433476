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
#include "lammps.h"
#include "update.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
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
  h_cache = h;
}

static std::string show(double x)
{
  std::ostringstream s;
  s.precision(12);
  s << x;
  return s.str();
}

// a finite number, or false
static bool number(const std::string &text, double &out)
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
        " numbers after E_inf (an odd count: E_" + std::to_string(nprony / 2 + 1) + " has no beta_" +
        std::to_string(nprony / 2 + 1) + ")";
  Law out;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const bool is_beta = k > 0 && k % 2 == 0;
    const std::string name = k == 0 ? "E_inf" : (is_beta ? "beta_" : "E_") + std::to_string((k + 1) / 2);
    const std::string unit = is_beta ? "1/s" : "Pa";
    double x = 0.0;
    if (!number(args[k], x))
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

double simulation_time(LAMMPS_NS::LAMMPS *lmp)
{
  const LAMMPS_NS::Update *update = lmp->update;
  return update->atime + static_cast<double>(update->ntimestep - update->atimestep) * update->dt;
}

void Store::begin(bigint step_, double now_, double dt_, int maxterms)
{
  ++call;
  step = step_;
  now = now_;
  dt = dt_;
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

double Store::advance(const Key &key, Law &law, double u)
{
  std::size_t r;
  auto found = index.find(key);
  if (found == index.end()) {
    // first touch: the internal variables start at zero, one step ago, with u = 0
    r = recs.size();
    recs.push_back({key, step, now - dt, now, 0.0, 0.0, call});
    q.resize((r + 1) * 2 * stride, 0.0);
    index.emplace(key, r);
  } else {
    r = found->second;
    Rec &c = recs[r];
    if (c.step != step) {
      // a new time step: the state of the last one becomes the accepted previous state
      double *qp = &q[2 * r * stride];
      for (int i = 0; i < stride; ++i) qp[i] = qp[stride + i];
      c.t_prev = c.t_cur;
      c.u_prev = c.u_cur;
      c.step = step;
    }
  }
  Rec &c = recs[r];
  double h = now - c.t_prev;
  if (h < 0.0) {
    backwards = true;
    h = 0.0;
  }
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
  c.t_cur = now;
  c.call = call;
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
  backwards = false;
}

double Store::memory_usage() const
{
  return static_cast<double>(recs.capacity() * sizeof(Rec) + q.capacity() * sizeof(double) +
                             index.size() * (sizeof(Key) + sizeof(std::size_t) + 2 * sizeof(void *)));
}

}    // namespace vcor
