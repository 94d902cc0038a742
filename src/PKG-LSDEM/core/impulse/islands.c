/* islands.c -- contact islands (report §4.5, Figure 4.9) as connected components of the
 * contact graph: union-find with path halving and union by size, labelled by the
 * smallest global id of each island, and the step of the cross-rank label merge. The
 * report's Algorithm 4 (Cuthill-McKee on rank 0) is replaced by this: near-linear, and
 * every rank finds its islands itself. */
#include "lsdem_impulse.h"

int32_t lsdem_islands_find(int32_t *parent, int32_t i)
{
  while (parent[i] != i) {
    parent[i] = parent[parent[i]]; /* path halving */
    i = parent[i];
  }
  return i;
}

/* Joins the islands of i and j; the larger keeps its root (shorter paths). Returns the
 * root of the union. */
static int32_t unite(int32_t *parent, int32_t *size, int32_t i, int32_t j)
{
  int32_t ri = lsdem_islands_find(parent, i), rj = lsdem_islands_find(parent, j);
  if (ri == rj) return ri;
  if (size[ri] < size[rj]) {
    const int32_t t = ri;
    ri = rj;
    rj = t;
  }
  parent[rj] = ri;
  size[ri] += size[rj];
  return ri;
}

int lsdem_islands_build(int n, const int64_t *id, int npairs, const int32_t *pairs,
                        int32_t *parent, int32_t *size, int64_t *label)
{
  for (int32_t i = 0; i < n; i++) {
    parent[i] = i;
    size[i] = 1;
    label[i] = id[i];
  }
  for (int k = 0; k < npairs; k++) {
    const int32_t i = pairs[2 * k], j = pairs[2 * k + 1];
    if (i < 0 || j < 0) continue; /* a wall: not a vertex of the graph */
    const int64_t li = label[lsdem_islands_find(parent, i)];
    const int64_t lj = label[lsdem_islands_find(parent, j)];
    const int32_t r = unite(parent, size, i, j);
    label[r] = li < lj ? li : lj;
  }
  int islands = 0;
  for (int32_t i = 0; i < n; i++) {
    const int32_t r = lsdem_islands_find(parent, i);
    islands += r == i;
    label[i] = label[r];
  }
  return islands;
}

int lsdem_islands_merge(int n, int32_t *parent, int64_t *label, int m, const int32_t *body,
                        const int64_t *nlabel)
{
  int changed = 0;
  for (int k = 0; k < m; k++) {
    const int32_t r = lsdem_islands_find(parent, body[k]);
    if (nlabel[k] < label[r]) {
      label[r] = nlabel[k];
      changed = 1;
    }
  }
  for (int32_t i = 0; i < n; i++) label[i] = label[lsdem_islands_find(parent, i)];
  return changed;
}

lsdem_status lsdem_islands_validate(int n, const int32_t *parent, const int64_t *label,
                                    lsdem_error *err)
{
  for (int32_t i = 0; i < n; i++) {
    int32_t r = i, steps = 0;
    while (r >= 0 && r < n && parent[r] != r && steps <= n) {
      r = parent[r];
      steps++;
    }
    if (r < 0 || r >= n || steps > n)
      return lsdem_fail(err, LSDEM_ERR_ARG, "islands: body %d has no root (parent %d)",
                        (int)i, (int)parent[i]);
    if (label[i] != label[r])
      return lsdem_fail(err, LSDEM_ERR_ARG,
                        "islands: body %d is labelled %lld, its root %d %lld", (int)i,
                        (long long)label[i], (int)r, (long long)label[r]);
  }
  return LSDEM_OK;
}
