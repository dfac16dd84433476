// SPDX-License-Identifier: GPL-2.0-only
//
// pair_style vcor/hereditary: vcor's hereditary Hertz contact between finite-size spheres
// (vcor_hereditary.h). Normal force only; one MPI rank.
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#ifndef VCOR_PAIR_HEREDITARY_H
#define VCOR_PAIR_HEREDITARY_H

#include "pair.h"
#include "vcor_hereditary.h"

#include <vector>

namespace LAMMPS_NS {

class PairVcorHereditary : public Pair {
 public:
  PairVcorHereditary(class LAMMPS *);
  ~PairVcorHereditary() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  double memory_usage() override;
  void *extract(const char *, int &) override;

 protected:
  std::vector<vcor::Law> laws;    // (ntypes+1)^2, [i*(ntypes+1)+j]
  std::vector<double> maxrad;     // largest radius per atom type (m)
  vcor::Store store;
  double ncontacts;               // contacts evaluated in the last compute()
  double nmin;                    // the smallest n of the time-step rule among the contacts ended so far
  int maxterms;
  int stride;                     // ntypes + 1 when allocated
  vcor::RunId warned;             // the run the time-step warning was last given in
  bool warned_overlap = false;     // the large-overlap warning is given once

  void allocate();
  vcor::Law &law(int i, int j) { return laws[i * stride + j]; }
};

}    // namespace LAMMPS_NS

#endif
