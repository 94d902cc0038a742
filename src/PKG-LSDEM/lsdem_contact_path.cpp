// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: one grain's contacts, pose -> state -> manifold -> law ->
   commit (lsdem_contact_path.h).
------------------------------------------------------------------------- */

#include "lsdem_contact_path.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "fix_lsdem_history.h"

#include <algorithm>
#include <cstdlib>
#include <new>

using namespace LAMMPS_NS;

LsdemContactPath::LsdemContactPath() : store(nullptr), lane(0), points(nullptr), cap(0)
{
  m = lsdem_manifold_over(nullptr, 0);
}

LsdemContactPath::~LsdemContactPath()
{
  free(points);
}

/* ---------------------------------------------------------------------- */

void LsdemContactPath::setup(FixLsdemHistory *history, const AtomVecLsdem *avec, int lane_id,
                             int min_points)
{
  store = history;
  lane = lane_id;
  int need = std::max(1, min_points);
  for (int s = 0; s < avec->nshapes(); s++)
    need = std::max(need, lsdem_manifold_capacity(lsdem_library_shape(avec->library(), s)));
  if (need > cap) {
    free(points);
    points = (lsdem_contact_point *) malloc(sizeof(lsdem_contact_point) * need);
    if (!points) throw std::bad_alloc();
    cap = need;
  }
  m = lsdem_manifold_over(points, cap);
}

/* ---------------------------------------------------------------------- */

void LsdemContactPath::pose_of(const Atom *atom, const AtomVecLsdem *avec, int i, lsdem_pose &p)
{
  for (int d = 0; d < 3; d++) {
    p.x[d] = atom->x[i][d];
    p.v[d] = atom->v[i][d];
    p.omega[d] = atom->omega[i][d];
  }
  if (avec->shape_of(i)->sdf.kind == LSDEM_SDF_SPHERE) {
    // an analytic sphere's level set is the same in every orientation: no lookup in it
    // needs its turn (the sphere tests its partners; only a setup check looks up in it)
    static const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::copy(identity, identity + 9, p.R);
  } else {
    lsdem_quat_to_matrix(avec->quat[i], p.R);
  }
}

/* ---------------------------------------------------------------------- */

void LsdemContactPath::begin_step(int nlanes)
{
  if (store) store->begin_step(nlanes);
}

void LsdemContactPath::begin_atom()
{
  if (store) store->begin_atom(lane);
}

void LsdemContactPath::end_atom(int i)
{
  if (store) store->end_atom(lane, i);
}

void LsdemContactPath::end_step()
{
  if (store) store->end_step();
}

bool LsdemContactPath::keeps_state(int i) const
{
  return store && store->holds(i);
}

/* ---------------------------------------------------------------------- */

bool LsdemContactPath::touched(int i, tagint partner) const
{
  lsdem_pair_state in;
  return store && store->find(i, partner, in) && in.nshear > 0;
}

/* ---------------------------------------------------------------------- */

int LsdemContactPath::test(int i, tagint partner, const lsdem_shape *A, const lsdem_pose &pa,
                           const lsdem_shape *B, const lsdem_pose &pb,
                           const lsdem_contact_params &prm, bigint step,
                           lsdem_contact_result &res)
{
  if (A->sdf.kind == LSDEM_SDF_SPHERE)
    return test_sphere(i, partner, A->sdf.a[0], pa, B, pb, prm, step, res);
  if (!store || !(prm.law.mu > 0.0 || prm.detect.node_skin > 0.0)) {
    lsdem_contact_penalty(A, &pa, B, &pb, &prm, step, nullptr, nullptr, &m, &res);
    return res.npen;
  }
  lsdem_pair_state in;
  const bool found = store->find(i, partner, in);
  lsdem_pair_state out =
      store->reserve(lane, lsdem_nodelist_capacity(A), lsdem_manifold_capacity(A));
  lsdem_detect(A, &pa, B, &pb, &prm.detect, step, found ? &in.list : nullptr, &out.list, &m);
  FixLsdemHistory::place_shear(out);  // behind the list just written: one stream per step
  lsdem_penalty_apply(&m, &prm.law, prm.dt, step, found ? in.shear : nullptr,
                      found ? in.nshear : 0, out.shear, &out.nshear, &res);
  store->commit(lane, partner, out);
  return res.npen;
}

/* ---------------------------------------------------------------------- */

int LsdemContactPath::test_points(int i, tagint partner, const lsdem_band *band,
                                  const lsdem_band_points &pts, const lsdem_pose &pw,
                                  const lsdem_shape *B, const lsdem_pose &pb,
                                  const lsdem_contact_params &prm, bigint step,
                                  lsdem_contact_result &res)
{
  lsdem_detect_band_points(band, &pts, &pw, B, &pb, &m);
  lsdem_pair_state in;
  const bool keep = store && prm.law.mu > 0.0, found = keep && store->find(i, partner, in);
  lsdem_pair_state out;
  if (keep) {
    out = store->reserve(lane, 0, m.n);
    FixLsdemHistory::place_shear(out);
  }
  lsdem_penalty_apply(&m, &prm.law, prm.dt, step, found ? in.shear : nullptr,
                      found ? in.nshear : 0, keep ? out.shear : nullptr,
                      keep ? &out.nshear : nullptr, &res);
  if (keep) store->commit(lane, partner, out);
  return res.npen;
}

/* ---------------------------------------------------------------------- */

int LsdemContactPath::detect(int i, tagint partner, const lsdem_shape *A, const lsdem_pose &pa,
                             const lsdem_shape *B, const lsdem_pose &pb,
                             const lsdem_detect_params &det, bigint step)
{
  if (!store || !(det.node_skin > 0.0)) {
    lsdem_detect(A, &pa, B, &pb, &det, step, nullptr, nullptr, &m);
    return m.n;
  }
  lsdem_pair_state in;
  const bool found = store->find(i, partner, in);
  lsdem_pair_state out = store->reserve(lane, lsdem_nodelist_capacity(A), 0);
  lsdem_detect(A, &pa, B, &pb, &det, step, found ? &in.list : nullptr, &out.list, &m);
  out.nshear = 0;
  store->commit(lane, partner, out);
  return m.n;
}

/* ----------------------------------------------------------------------
   an analytic sphere: its one contact point by the core (lsdem_contact_sphere), the same
   result as the general path's; only friction needs a state (a sphere keeps no node
   list), one shear entry
------------------------------------------------------------------------- */

int LsdemContactPath::test_sphere(int i, tagint partner, double ra, const lsdem_pose &pa,
                                  const lsdem_shape *B, const lsdem_pose &pb,
                                  const lsdem_contact_params &prm, bigint step,
                                  lsdem_contact_result &res)
{
  if (!store || !(prm.law.mu > 0.0))
    return lsdem_contact_sphere(ra, &pa, B, &pb, &prm.law, prm.dt, step, nullptr, 0, nullptr,
                                nullptr, &res);
  lsdem_pair_state in;
  const bool found = store->find(i, partner, in);
  lsdem_pair_state out = store->reserve(lane, 0, 1);
  FixLsdemHistory::place_shear(out);
  lsdem_contact_sphere(ra, &pa, B, &pb, &prm.law, prm.dt, step, found ? in.shear : nullptr,
                       found ? in.nshear : 0, out.shear, &out.nshear, &res);
  store->commit(lane, partner, out);
  return res.npen;
}
