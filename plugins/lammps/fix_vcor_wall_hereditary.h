// SPDX-License-Identifier: GPL-2.0-only
//
// fix vcor/wall/hereditary: vcor's hereditary Hertz contact (vcor_hereditary.h) between spheres
// and a flat rigid wall. Normal force only; one MPI rank.
//
// This file is part of vcor's LAMMPS plugin and is distributed under the GNU General Public
// License version 2 (see LICENSE in this folder).

#ifndef VCOR_FIX_WALL_HEREDITARY_H
#define VCOR_FIX_WALL_HEREDITARY_H

#include "fix.h"
#include "vcor_hereditary.h"

namespace LAMMPS_NS {

class FixVcorWallHereditary : public Fix {
 public:
  FixVcorWallHereditary(class LAMMPS *, int, char **);
  ~FixVcorWallHereditary() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void min_setup(int) override;
  void post_force(int) override;
  void min_post_force(int) override;
  double compute_vector(int) override;
  double memory_usage() override;

 protected:
  int dim;                  // 0, 1, 2: the wall's normal
  bool has_lo, has_hi;
  double lo, hi;            // wall positions (m)
  vcor::Law law;
  vcor::Store store;
  double wall_force[3];         // total force of the walls on the group (N)
  double ncontacts;            // touching contacts
  double nmin;                 // the smallest n of the time-step rule among the contacts ended so far
  vcor::RunId warned;          // the run the time-step warning was last given in
  bool warned_overlap = false;  // the large-overlap warning is given once
};

}    // namespace LAMMPS_NS

#endif
