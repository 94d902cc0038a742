// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: the warm-start store of impulse mode's resting contacts
   (lsdem_impulse_warm.h).
------------------------------------------------------------------------- */

#include "lsdem_impulse_warm.h"

#include "lmptype.h"

#include <algorithm>

using namespace LAMMPS_NS;

void LsdemImpulseWarm::grow(int nmax)
{
  if ((int) entries.size() < nmax) entries.resize(nmax);
}

bool LsdemImpulseWarm::take(int i, tagint partner, const double xb[3], double radius,
                            double P[3])
{
  Entry *best = nullptr;
  double best2 = radius * radius;
  for (Entry &e : entries[i]) {
    if (e.partner != partner || e.taken) continue;
    const double d[3] = {e.xb[0] - xb[0], e.xb[1] - xb[1], e.xb[2] - xb[2]};
    const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (d2 <= best2) {  // ties: the first stored (the previous step's contact order)
      if (best && d2 == best2) continue;
      best = &e;
      best2 = d2;
    }
  }
  if (!best) {
    P[0] = P[1] = P[2] = 0.0;
    return false;
  }
  best->taken = true;
  for (int d = 0; d < 3; d++) P[d] = best->P[d];
  return true;
}

void LsdemImpulseWarm::add(int i, tagint partner, const double xb[3], const double P[3])
{
  Entry e;
  e.partner = partner;
  e.taken = false;
  for (int d = 0; d < 3; d++) {
    e.xb[d] = xb[d];
    e.P[d] = P[d];
  }
  entries[i].push_back(e);
  most = std::max(most, (int) entries[i].size());
}

int LsdemImpulseWarm::pack(int i, double *buf) const
{
  int m = 0;
  buf[m++] = ubuf((int64_t) entries[i].size()).d;
  for (const Entry &e : entries[i]) {
    buf[m++] = ubuf((int64_t) e.partner).d;
    for (int d = 0; d < 3; d++) buf[m++] = e.xb[d];
    for (int d = 0; d < 3; d++) buf[m++] = e.P[d];
  }
  return m;
}

int LsdemImpulseWarm::unpack(int i, const double *buf)
{
  int m = 0;
  const int n = (int) ubuf(buf[m++]).i;
  entries[i].clear();
  for (int k = 0; k < n; k++) {
    Entry e;
    e.partner = (tagint) ubuf(buf[m++]).i;
    for (int d = 0; d < 3; d++) e.xb[d] = buf[m++];
    for (int d = 0; d < 3; d++) e.P[d] = buf[m++];
    e.taken = false;
    entries[i].push_back(e);
  }
  most = std::max(most, n);
  return m;
}

double LsdemImpulseWarm::memory_usage() const
{
  double bytes = (double) entries.capacity() * sizeof(std::vector<Entry>);
  for (const auto &v : entries) bytes += (double) v.capacity() * sizeof(Entry);
  return bytes;
}
