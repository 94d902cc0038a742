// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem. All contact physics is in the core (lsdem_contact_nodes and the
   sphere fast paths); this file decides who is master of each pair, passes the
   master's history slice, and scatters the results (doc/pair_lsdem.rst).
------------------------------------------------------------------------- */

#include "pair_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lsdem_history.h"
#include "fix_lsdem_sphere_shear.h"
#include "force.h"
#include "lsdem_lammps_compat.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

// setup warns when a node penetrates deeper than this fraction of the smaller grain's
// equivalent-sphere radius (grains generated or imported overlapping)
static constexpr double OVERLAP_WARN = LsdemContactOptions::OVERLAP_WARN;
static const char HISTORY_ID[] = "LSDEM_PAIR_HISTORY";
static const char SPHERE_SHEAR_ID[] = "LSDEM_PAIR_SPHERE_SHEAR";

/* ---------------------------------------------------------------------- */

PairLsdem::PairLsdem(LAMMPS *lmp) :
  Pair(lmp), mode(LSDEM_ROLES_ONEWAY), zcap(0), params(nullptr),
  onerad(nullptr), maxrad(nullptr), kn_max(0.0), kn_law_max(0.0), avec(nullptr), fix_history(nullptr),
  sphere_shear(nullptr),
  nmax_atom(0), pose(nullptr), shape(nullptr), ncount(nullptr), grain_node_tests(nullptr),
  master_built(0), nmax_master(0), maxmaster(0), master_first(nullptr), master_num(nullptr),
  master_j(nullptr), master_scale_of(nullptr), nlanes(1), contact_step(-1)
{
  single_enable = 0;
  finitecutflag = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  comm_forward = 1;  // contact counts, for zcap
  comm_reverse = 1;
  // workload of the last force call, for compute pair: pairs tested, contacts,
  // nodes looked up, penetrating nodes; the contact state it left: bytes of the history
  // store (reserved), pair states, node-list entries, shear entries, bytes the states take
  // (compute pair sums over ranks)
  nextra = 9;
  pvector = new double[nextra];
  for (int k = 0; k < nextra; k++) pvector[k] = 0.0;
}

/* ---------------------------------------------------------------------- */

PairLsdem::~PairLsdem()
{
  delete[] pvector;
  int ifix = modify->find_fix(HISTORY_ID);
  if (fix_history && ifix >= 0) modify->delete_fix(ifix);
  ifix = modify->find_fix(SPHERE_SHEAR_ID);
  if (sphere_shear && ifix >= 0) modify->delete_fix(ifix);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(params);
    delete[] onerad;
    delete[] maxrad;
  }
  memory->sfree(pose);
  memory->sfree(shape);
  memory->destroy(ncount);
  memory->destroy(grain_node_tests);
  memory->destroy(master_first);
  memory->destroy(master_num);
  memory->destroy(master_j);
  memory->destroy(master_scale_of);
}

/* ---------------------------------------------------------------------- */

PairLsdem *PairLsdem::of(Force *force)
{
  Pair *p = force->pair_match("lsdem", 1);
  if (!p) p = force->pair_match("lsdem/omp", 1);
  return dynamic_cast<PairLsdem *>(p);
}

/* ---------------------------------------------------------------------- */

void PairLsdem::allocate()
{
  allocated = 1;
  int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(params, n + 1, n + 1, "pair:params");
  memset(&params[0][0], 0, sizeof(lsdem_contact_params) * (n + 1) * (n + 1));
  onerad = new double[n + 1];
  maxrad = new double[n + 1];
}

/* ----------------------------------------------------------------------
   pair_style lsdem [mode oneway|twoway] [master nodes|id] [normal node|traction]
                    [stride N] [zcap N] [nodelist auto|off|skin]
------------------------------------------------------------------------- */

void PairLsdem::settings(int narg, char **arg)
{
  bool oneway = true, by_id = false;
  global = LsdemContactOptions();
  zcap = 0;
  for (int iarg = 0; iarg < narg; iarg += 2) {
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style lsdem: keyword {} needs a value", arg[iarg]);
    std::string key = arg[iarg], val = arg[iarg + 1];
    if (global.read_keyword(lmp, "pair_style lsdem", key, arg[iarg + 1],
                            LsdemContactOptions::NORMAL | LsdemContactOptions::DETECT))
      continue;
    if (key == "mode") {
      if (val == "oneway") oneway = true;
      else if (val == "twoway") oneway = false;
      else error->all(FLERR, "pair_style lsdem: mode must be oneway or twoway, not {}", val);
    } else if (key == "master") {
      if (val == "nodes") by_id = false;
      else if (val == "id") by_id = true;
      else error->all(FLERR, "pair_style lsdem: master must be nodes or id, not {}", val);
    } else if (key == "zcap") {
      zcap = utils::inumeric(FLERR, val.c_str(), false, lmp);
      if (zcap < 0) error->all(FLERR, "pair_style lsdem: zcap must be >= 0 (0 = off)");
    } else error->all(FLERR, "pair_style lsdem: unknown keyword {}", key);
  }
  if (by_id && !oneway) error->all(FLERR, "pair_style lsdem: master id is for mode oneway");
  mode = !oneway ? LSDEM_ROLES_TWOWAY : by_id ? LSDEM_ROLES_ONEWAY_ID : LSDEM_ROLES_ONEWAY;
}

/* ----------------------------------------------------------------------
   pair_coeff I J kn ks mu [cn value] [ct value]
------------------------------------------------------------------------- */

void PairLsdem::coeff(int narg, char **arg)
{
  if (narg < 5 || (narg - 5) % 2)
    error->all(FLERR, "pair_coeff for lsdem: expected I J kn ks mu [cn value] [ct value]");
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  LsdemContactOptions c;
  c.read_stiffness(lmp, "pair_coeff for lsdem", arg + 2);
  for (int iarg = 5; iarg < narg; iarg += 2)
    if (!c.read_keyword(lmp, "pair_coeff for lsdem", arg[iarg], arg[iarg + 1],
                        LsdemContactOptions::DAMPING))
      error->all(FLERR, "pair_coeff for lsdem: unknown keyword {}", arg[iarg]);
  c.check_law(lmp, "pair_coeff for lsdem");
  lsdem_contact_params p;
  memset(&p, 0, sizeof(p));
  p.law = c.law;

  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      params[i][j] = p;
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
}

/* ---------------------------------------------------------------------- */

void PairLsdem::init_style()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Pair style lsdem requires atom_style lsdem");
  if (!atom->tag_enable) error->all(FLERR, "Pair style lsdem requires atom IDs");
  if (force->newton_pair == 0)
    error->all(FLERR, "Pair style lsdem requires newton pair on (add 'newton on')");
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "Pair style lsdem requires ghost velocities (add 'comm_modify vel yes')");

  // a plain full list: each grain tests its own nodes against every neighbour
  LsdemCompat::request_full_list(neighbor, this, instance_me);

  // largest bounding radius per type over all ranks: cutoff = maxrad[I] + maxrad[J]
  int ntypes = atom->ntypes;
  for (int t = 1; t <= ntypes; t++) onerad[t] = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    onerad[atom->type[i]] = std::max(onerad[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(&onerad[1], &maxrad[1], ntypes, MPI_DOUBLE, MPI_MAX, world);
  check_periodic_length();
  kn_max = stiffest_node_spring();
  // the flat-contact node counts depend on the shape alone: kept over runs
  if ((int) flat_nodes.size() != avec->nshapes()) flat_nodes.assign(avec->nshapes(), -1.0);
  node_scale.resize(avec->nshapes());
  for (int s = 0; s < avec->nshapes(); s++)
    node_scale[s] = lsdem_contact_node_scale(lsdem_library_shape(avec->library(), s));
  LsdemContactOptions::sum_quanta(kn_max, avec, force_q, torque_q);

  // history where friction is on or node lists are kept; none at all when mu == 0
  // everywhere and node lists are off
  int friction = 0;
  for (int i = 1; i <= ntypes; i++)
    for (int j = i; j <= ntypes; j++)
      if (setflag[i][j] && params[i][j].law.mu > 0.0) friction = 1;
  // fixed IDs, so restart files find them again (pair gran appends instance_me, which
  // differs when a script clears and re-reads a restart within one process); sphere
  // masters keep their springs apart (fix_lsdem_sphere_shear.h)
  if (friction || global.detect(avec).node_skin > 0.0)
    fix_history = internal_fix<FixLsdemHistory>(HISTORY_ID, "LSDEM_HISTORY");
  if (friction) sphere_shear = internal_fix<FixLsdemSphereShear>(SPHERE_SHEAR_ID, "LSDEM_SPHERE_SHEAR");
  set_lanes(1);
}

/* ----------------------------------------------------------------------
   the internal fix of this ID and style, made when it does not exist yet
------------------------------------------------------------------------- */

template <class F> F *PairLsdem::internal_fix(const char *fix_id, const char *style)
{
  const int ifix = modify->find_fix(fix_id);
  Fix *fix = ifix >= 0 ? modify->fix[ifix]
                       : modify->add_fix(fmt::format("{} all {}", fix_id, style));
  F *f = dynamic_cast<F *>(fix);
  if (!f) error->all(FLERR, "Fix ID {} is reserved for pair lsdem", fix_id);
  return f;
}

/* ----------------------------------------------------------------------
   n lanes (threads) with their contact paths set up for this run
------------------------------------------------------------------------- */

void PairLsdem::set_lanes(int n)
{
  while ((int) lanes.size() < n) lanes.emplace_back(new Lane);
  for (int l = 0; l < (int) lanes.size(); l++) lanes[l]->path.setup(fix_history, avec, l);
}

/* ----------------------------------------------------------------------
   a grain must not touch two periodic images of the same partner: each periodic box
   length must exceed twice the largest bounding radius
------------------------------------------------------------------------- */

void PairLsdem::check_periodic_length() const
{
  const double rmax = *std::max_element(&maxrad[1], &maxrad[1] + atom->ntypes);
  const int periodic[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  for (int d = 0; d < 3; d++)
    if (periodic[d] && domain->prd[d] <= 2.0 * rmax)
      error->all(FLERR, "pair lsdem: the periodic box is {:.6g} long in {}, not longer than "
                 "twice the largest grain bounding radius ({:.6g}): a grain would touch two "
                 "images of one partner; enlarge the box", domain->prd[d], "xyz"[d], 2.0 * rmax);
}

/* ---------------------------------------------------------------------- */

double PairLsdem::init_one(int i, int j)
{
  if (setflag[i][j] == 0)
    error->all(FLERR, "pair_coeff {} {} is not set (pair_style lsdem does not mix)", i, j);
  params[i][j].dt = update->dt;
  params[i][j].law.normal = global.law.normal;
  params[i][j].detect = global.detect(avec);
  params[j][i] = params[i][j];
  return maxrad[i] + maxrad[j];
}

/* ----------------------------------------------------------------------
   largest per-node normal stiffness (force/length) of any type pair
------------------------------------------------------------------------- */

double PairLsdem::stiffest_node_spring()
{
  kn_law_max = 0.0;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j]) kn_law_max = std::max(kn_law_max, params[i][j].law.kn);
  return LsdemContactOptions::node_spring(kn_law_max, global.law.normal, global.stride, avec);
}

/* ---------------------------------------------------------------------- */

double PairLsdem::stiffest_contact(int s, double &nodes)
{
  if (flat_nodes[s] < 0.0)  // once per shape (the normal law is the style's): a node scan
    flat_nodes[s] = lsdem_flat_contact_nodes(lsdem_library_shape(avec->library(), s),
                                             global.law.normal);
  nodes = flat_nodes[s];
  return kn_law_max * nodes;
}

/* ---------------------------------------------------------------------- */

void PairLsdem::reset_dt()
{
  if (!allocated) return;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = 1; j <= atom->ntypes; j++) params[i][j].dt = update->dt;
}

/* ---------------------------------------------------------------------- */

void PairLsdem::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  begin_force_call(1);
  update_poses(0, atom->nlocal + atom->nghost);
  if (neighbor->ago == 0 || !master_built) build_master_pairs();  // the list was just built
  test_pairs(*lanes[0], 0, list->inum);
  end_force_call();
  if (zcap > 0) coordination(1);
  apply_contacts(*lanes[0], atom->f, atom->torque);
  if (eflag_global) tally_workload(contacting_pairs());  // compute pair reads it then only
  if (update->setupflag) report_overlaps();
  if (vflag_fdotr) virial_fdotr_compute();
}

/* ----------------------------------------------------------------------
   a force call's start: its lanes emptied, the pair states' pool opened for them
------------------------------------------------------------------------- */

void PairLsdem::begin_force_call(int n)
{
  nlanes = n;
  for (int l = 0; l < n; l++) {
    Lane &lane = *lanes[l];
    lane.contact.clear();
    lane.ntested_pairs = lane.ntested_nodes = lane.npen_nodes = 0;
  }
  contact_step = update->ntimestep;
  if (atom->nmax > nmax_atom) {
    memory->grow(grain_node_tests, atom->nmax, "pair:grain_node_tests");
    std::fill(grain_node_tests + nmax_atom, grain_node_tests + atom->nmax, 0);  // not yet
    nmax_atom = atom->nmax;
    pose = (lsdem_pose *) memory->srealloc(pose, sizeof(lsdem_pose) * nmax_atom, "pair:pose");
    shape = (const lsdem_shape **) memory->srealloc(shape, sizeof(lsdem_shape *) * nmax_atom,
                                                    "pair:shape");
    memory->destroy(ncount);
    memory->create(ncount, nmax_atom, "pair:ncount");
  }
  lanes[0]->path.begin_step(n);
}

void PairLsdem::end_force_call()
{
  lanes[0]->path.end_step();
}

/* ----------------------------------------------------------------------
   the master pairs of the local grains ilist[iifrom..iito), by one lane, with each
   grain's node tests into grain_node_tests
------------------------------------------------------------------------- */

void PairLsdem::test_pairs(Lane &lane, int iifrom, int iito)
{
  const int *ilist = list->ilist;
  for (int ii = iifrom; ii < iito; ii++) {
    const int i = ilist[ii];
    const bigint before = lane.ntested_nodes;
    test_grain(lane, i);
    grain_node_tests[i] = (int) (lane.ntested_nodes - before);
  }
}

/* ----------------------------------------------------------------------
   the master pairs of local grain i whose bounding spheres overlap, by one lane
------------------------------------------------------------------------- */

void PairLsdem::test_grain(Lane &lane, int i)
{
  const int *js = master_j + master_first[i];
  const double *scales = master_scale_of + master_first[i];
  if (keeps_sphere_slots(i)) {
    // a sphere master: its springs in its slots, one per master pair, in place
    lsdem_shear_hist *slot = sphere_shear->slots(i);
    for (int k = 0; k < master_num[i]; k++) {
      if (bounding_spheres_overlap(i, js[k])) test_pair(lane, i, js[k], scales[k], &slot[k]);
      else FixLsdemSphereShear::drop(slot[k]);
    }
    return;
  }
  lane.path.begin_atom();
  for (int k = 0; k < master_num[i]; k++) {
    const int j = js[k];
    if (bounding_spheres_overlap(i, j)) test_pair(lane, i, j, scales[k], nullptr);
  }
  lane.path.end_atom(i);
}

/* ----------------------------------------------------------------------
   poses and shapes of local+ghost grains from..to-1 for this force call
------------------------------------------------------------------------- */

void PairLsdem::update_poses(int from, int to)
{
  for (int i = from; i < to; i++) {
    LsdemContactPath::pose_of(atom, avec, i, pose[i]);
    shape[i] = avec->shape_of(i);
  }
}

/* ----------------------------------------------------------------------
   the neighbor list's pairs in which i is master (master_scale > 0), per local atom i,
   kept until the list is rebuilt (tags, shapes and atom indices stay put till then)
------------------------------------------------------------------------- */

void PairLsdem::build_master_pairs()
{
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  if (atom->nlocal > nmax_master) {
    nmax_master = atom->nmax;
    memory->destroy(master_first);
    memory->destroy(master_num);
    memory->create(master_first, nmax_master, "pair:master_first");
    memory->create(master_num, nmax_master, "pair:master_num");
  }
  for (int i = 0; i < atom->nlocal; i++) master_first[i] = master_num[i] = 0;
  int n = 0;
  for (int ii = 0; ii < inum; ii++) n += numneigh[ilist[ii]];
  if (n > maxmaster) {
    maxmaster = n;
    memory->destroy(master_j);
    memory->destroy(master_scale_of);
    memory->create(master_j, maxmaster, "pair:master_j");
    memory->create(master_scale_of, maxmaster, "pair:master_scale");
  }
  n = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    master_first[i] = n;
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = firstneigh[i][jj] & NEIGHMASK;
      const double scale =
          lsdem_contact_roles(shape[i], node_scale[avec->shape[i]], atom->tag[i], shape[j],
                              node_scale[avec->shape[j]], atom->tag[j], mode);
      if (scale == 0.0) continue;
      master_j[n] = j;
      master_scale_of[n++] = scale;
    }
    master_num[i] = n - master_first[i];
    if (keeps_sphere_slots(i)) assign_sphere_slots(i);
  }
  master_built = 1;
}

/* ----------------------------------------------------------------------
   sphere master i's slots := one per master pair, with the springs it held; a spring
   the general store holds instead (a restart file of an earlier version) is taken over
------------------------------------------------------------------------- */

void PairLsdem::assign_sphere_slots(int i)
{
  partner_tags.resize(master_num[i]);
  for (int k = 0; k < master_num[i]; k++) partner_tags[k] = atom->tag[master_j[master_first[i] + k]];
  sphere_shear->assign(i, partner_tags.data(), master_num[i]);
  sphere_shear->take_over(i, fix_history);
}

/* ----------------------------------------------------------------------
   i's nodes (or i's sphere) against j's level set, through the shared contact path (a
   sphere master with its spring's slot: in place); the result is written in place of a
   new contact, which is kept when they touch
------------------------------------------------------------------------- */

inline void PairLsdem::test_pair(Lane &lane, int i, int j, double scale, lsdem_shear_hist *slot)
{
  lane.contact.emplace_back();
  Contact &c = lane.contact.back();
  const lsdem_contact_params &prm = params[atom->type[i]][atom->type[j]];
  const int npen =
      slot ? LsdemContactPath::test_sphere_in_place(shape[i]->sdf.a[0], pose[i], shape[j],
                                                    pose[j], prm, contact_step, *slot, c.res)
           : lane.path.test(i, atom->tag[j], shape[i], pose[i], shape[j], pose[j], prm,
                            contact_step, c.res);
  lane.ntested_pairs++;
  lane.ntested_nodes += c.res.ntested;
  lane.npen_nodes += npen;
  if (npen == 0) {
    lane.contact.pop_back();
    return;
  }
  c.i = i;
  c.j = j;
  // the test made by the one-way master decides whether the pair is in contact
  c.counts = (scale == 1.0 || atom->tag[i] < atom->tag[j]) ? 1 : 0;
  c.scale = scale;
}

/* ----------------------------------------------------------------------
   force/torque on master i and the reaction on j (eqs 2.3, 2.5, 2.11, 2.15, 2.16).
   zcap (report §3.3.3): a pair whose grains have more than zcap contacts is scaled
   by zcap/count of the busier grain, equally on both sides (action = reaction).
------------------------------------------------------------------------- */

void PairLsdem::apply_contacts(Lane &lane, double **f, double **torque) const
{
  for (Contact &k : lane.contact) {
    if (zcap > 0) {  // kept in the contact: compute contact/lsdem reports the scaled force
      double busiest = std::max(ncount[k.i], ncount[k.j]);
      if (busiest > zcap) k.scale *= zcap / busiest;
    }
    // each grain's force and torque is a sum of these terms, over local contacts and
    // the ghosts' share LAMMPS sums back: rounded to the quanta, every order gives the
    // same sum (the same on any rank count, lsdem_quantum_for)
    lsdem_contact_terms t;
    lsdem_contact_terms_of(&k.res, k.scale, force_q, torque_q, &t);
    // row by row (each a short loop the compiler pairs up): the rows are distinct
    for (int d = 0; d < 3; d++) f[k.i][d] += t.force[d];
    for (int d = 0; d < 3; d++) torque[k.i][d] += t.torque_a[d];
    for (int d = 0; d < 3; d++) f[k.j][d] -= t.force[d];
    for (int d = 0; d < 3; d++) torque[k.j][d] += t.torque_b[d];
  }
}

/* ----------------------------------------------------------------------
   contacts per grain (partners with >= 1 penetrating node, eq 3.15) from the
   last force call, summed onto owners; to_ghosts also copies them to ghosts
------------------------------------------------------------------------- */

const double *PairLsdem::coordination(int to_ghosts)
{
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) ncount[i] = 0.0;
  for (int l = 0; l < nlanes; l++)
    for (const Contact &k : lanes[l]->contact)
      if (k.counts) {
        ncount[k.i] += 1.0;
        ncount[k.j] += 1.0;
      }
  LsdemCompat::reverse_comm(comm, this);
  if (to_ghosts) LsdemCompat::forward_comm(comm, this);
  return ncount;
}

/* ----------------------------------------------------------------------
   local workload of the last force call into pvector (see constructor); on the steps
   that tally energy only, the only steps compute pair may read it on
------------------------------------------------------------------------- */

void PairLsdem::tally_workload(double touching)
{
  for (int k = 0; k < nextra; k++) pvector[k] = 0.0;
  if (fix_history) {
    pvector[4] = fix_history->memory_usage();
    fix_history->held(pvector[5], pvector[6], pvector[7], pvector[8]);
  }
  if (sphere_shear) {  // a sphere master's pair state is its one spring
    const double springs = sphere_shear->springs_held();
    pvector[4] += sphere_shear->memory_usage();
    pvector[5] += springs;
    pvector[7] += springs;
    pvector[8] += springs * sizeof(lsdem_shear_hist);
  }
  for (int l = 0; l < nlanes; l++) {
    const Lane &lane = *lanes[l];
    pvector[0] += (double) lane.ntested_pairs;
    pvector[2] += (double) lane.ntested_nodes;
    pvector[3] += (double) lane.npen_nodes;
  }
  pvector[1] = touching;
}

/* the grain pairs in contact of the last force call (a pair found from both sides, in
   two-way mode, once) */

double PairLsdem::contacting_pairs() const
{
  double n = 0.0;
  for (int l = 0; l < nlanes; l++)
    for (const Contact &k : lanes[l]->contact) n += k.counts;
  return n;
}

/* ----------------------------------------------------------------------
   at setup: warn about grains that start heavily overlapping
------------------------------------------------------------------------- */

static double equivalent_radius(const lsdem_shape *s)
{
  return cbrt(3.0 * s->volume / (4.0 * MY_PI));
}

/* the deepest node of slave j's nodes in master i's level set: the test one-way contact
   (mode oneway) does not make, run at setup only, without history or forces */
double PairLsdem::reverse_depth(int i, int j)
{
  lsdem_contact_params prm = params[atom->type[i]][atom->type[j]];
  prm.law.mu = 0.0;
  prm.detect.node_skin = 0.0;  // no state: nothing read or kept
  lsdem_contact_result res;
  lanes[0]->path.test(j, atom->tag[i], shape[j], pose[j], shape[i], pose[i], prm,
                      update->ntimestep, res);
  return res.npen > 0 ? res.max_depth : 0.0;
}

void PairLsdem::report_overlaps()
{
  struct {
    double ratio;
    int rank;
  } mine = {0.0, comm->me}, worst;
  double info[5] = {0.0, 0.0, 0.0, 0.0, 0.0};  // tag i, tag j, depth, radius, reverse only
  bigint nover = 0, nover_all = 0;
  auto consider = [&](int i, int j, double depth, bool reverse) {
    const double req = std::min(equivalent_radius(shape[i]), equivalent_radius(shape[j]));
    const double ratio = depth / req;
    if (ratio > OVERLAP_WARN) nover++;
    if (ratio <= mine.ratio) return;
    mine.ratio = ratio;
    info[0] = (double) atom->tag[i];
    info[1] = (double) atom->tag[j];
    info[2] = depth;
    info[3] = req;
    info[4] = reverse ? 1.0 : 0.0;
  };
  for (int l = 0; l < nlanes; l++)
    for (const Contact &k : lanes[l]->contact) consider(k.i, k.j, k.res.max_depth, false);
  // a pair tested one way only (scale 1: mode oneway, or a sphere master) sees the master's
  // nodes only: a slave deep in (or wholly inside) its master shows in the reverse test
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    for (int k = master_first[i]; k < master_first[i] + master_num[i]; k++) {
      const int j = master_j[k];
      if (master_scale_of[k] != 1.0 || !bounding_spheres_overlap(i, j)) continue;
      const double depth = reverse_depth(i, j);
      if (depth > 0.0) consider(i, j, depth, true);
    }
  }
  MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (worst.ratio <= OVERLAP_WARN) return;
  MPI_Allreduce(&nover, &nover_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  MPI_Bcast(info, 5, MPI_DOUBLE, worst.rank, world);
  if (comm->me == 0)
    error->warning(FLERR,
                   "pair lsdem: {} contact tests find a node deeper than {:.0f}% of the smaller "
                   "grain's equivalent radius; deepest: grains {} and {}, depth {:.4g} = {:.1f}% "
                   "of {:.4g}. {}",
                   nover_all, 100.0 * OVERLAP_WARN, (tagint) info[0], (tagint) info[1], info[2],
                   100.0 * worst.ratio, info[3],
                   info[4] != 0.0
                       ? fmt::format("These are nodes of grain {} inside grain {}, which mode "
                                     "oneway does not test (it tests grain {}'s nodes): this "
                                     "overlap may exert little or no force. Separate the grains "
                                     "first, or use mode twoway", (tagint) info[1],
                                     (tagint) info[0], (tagint) info[0])
                       : std::string("Large repulsive forces follow: separate the grains first "
                                     "(e.g. a short run with a small time step, or a lower kn)"));
}

/* ---------------------------------------------------------------------- */

void *PairLsdem::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "kn_max") == 0) return (void *) &kn_max;
  // bond_style lsdem/net rounds its terms to (at least) this quantum: the balls' force
  // sums stay order-free with the contacts' terms in them
  if (strcmp(str, "force_quantum") == 0) return (void *) &force_q.q;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

int PairLsdem::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  for (int k = 0; k < n; k++) buf[k] = ncount[list[k]];
  return n;
}

void PairLsdem::unpack_forward_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) ncount[first + k] = buf[k];
}

int PairLsdem::pack_reverse_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) buf[k] = ncount[first + k];
  return n;
}

void PairLsdem::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int k = 0; k < n; k++) ncount[list[k]] += buf[k];
}

/* ----------------------------------------------------------------------
   restart: settings, then for each I <= J the setflag and coefficients
------------------------------------------------------------------------- */

void PairLsdem::write_restart_settings(FILE *fp)
{
  int v[4] = {(int) mode, (int) global.law.normal, global.stride, zcap};
  fwrite(v, sizeof(int), 4, fp);
  // nodelist is not stored: it changes no result, and files of earlier versions stay readable
}

void PairLsdem::read_restart_settings(FILE *fp)
{
  int v[4] = {0, 0, 0, 0};
  if (comm->me == 0) utils::sfread(FLERR, v, sizeof(int), 4, fp, nullptr, error);
  MPI_Bcast(v, 4, MPI_INT, 0, world);
  global = LsdemContactOptions();
  mode = (lsdem_roles_rule) v[0];
  global.law.normal = (lsdem_normal_law) v[1];
  global.stride = v[2];
  zcap = v[3];
}

void PairLsdem::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) {
        const lsdem_contact_params &p = params[i][j];
        double c[5] = {p.law.kn, p.law.ks, p.law.mu, p.law.cn, p.law.ct};
        fwrite(c, sizeof(double), 5, fp);
      }
    }
}

void PairLsdem::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (comm->me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (!setflag[i][j]) continue;
      double c[5];
      if (comm->me == 0) utils::sfread(FLERR, c, sizeof(double), 5, fp, nullptr, error);
      MPI_Bcast(c, 5, MPI_DOUBLE, 0, world);
      lsdem_penalty_law &p = params[i][j].law;
      p.kn = c[0];
      p.ks = c[1];
      p.mu = c[2];
      p.cn = c[3];
      p.ct = c[4];
    }
}

/* ----------------------------------------------------------------------
   interaction range for neighbor multi: the sum of bounding radii
------------------------------------------------------------------------- */

double PairLsdem::atom2cut(int i)
{
  return 2.0 * atom->radius[i];
}

double PairLsdem::radii2cut(double r1, double r2)
{
  return r1 + r2;
}

/* ---------------------------------------------------------------------- */

double PairLsdem::memory_usage()
{
  double bytes = (double) nmax_atom *
      (sizeof(lsdem_pose) + sizeof(lsdem_shape *) + sizeof(double) + sizeof(int));
  for (const auto &lane : lanes) bytes += (double) lane->contact.capacity() * sizeof(Contact);
  bytes += (double) nmax_master * 2 * sizeof(int);
  bytes += (double) maxmaster * (sizeof(int) + sizeof(double));
  return bytes;
}
