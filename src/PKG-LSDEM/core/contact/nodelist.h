/* nodelist.h -- the node lists of detection (nodelist.c), private to core/contact:
 * deciding whether a pair's list holds, building a new one while nodes are screened,
 * and the cells its entries keep. The public record types are in lsdem_contact.h. */
#ifndef LSDEM_CONTACT_NODELIST_H
#define LSDEM_CONTACT_NODELIST_H

#include "lsdem_contact.h"

#include <string.h>

/* The list state of one detection call. */
typedef struct {
  double skin;  /* s; 0: no list */
  double reach; /* L s: a looked-up node with phi >= reach is left out (HUGE_VAL: none) */
  double lip;   /* L (reach / skin) when finite */
  double margin; /* while built: the least distance a left-out node must move to touch */
  double cap;   /* the margin may not exceed this (grids: the gradient bound's limit) */
  int use;      /* the input list holds: look up its nodes only */
  int cached;   /* B is a grid: listed nodes' cells are kept */
  int building; /* a new list is being built into out */
  double moved; /* a list in use: the motion bound since it was built (list_motion) */
  double slack_unit; /* a list in use: its head's slack_unit */
  double slack_per_length; /* a list built: 1 / its slack unit, a trillionth less (0: none) */
  double inv_lip;          /* a list built with slack: 1 / lip, a trillionth less */
  int nslack;              /* a list built: entries with slack */
  const lsdem_nodelist_head *head_in;  /* the input list's head */
  const lsdem_nodelist_entry *node_in; /* and its entries (increasing node) */
  int nnode_in, node_cursor;
  lsdem_nodelist *out; /* where this step's list goes, or NULL (also without a skin) */
} node_list;


/* Decides whether in's list is used (pose of B in A's frame now: q = M x + t); when it is
 * not and out is given, starts a new one there. */
void nodelist_begin(node_list *L, const lsdem_shape *A, const lsdem_sdf *sdfB,
                    const lsdem_detect_params *det, int64_t step, const lsdem_nodelist *in,
                    lsdem_nodelist *out, const double M[9], const double t[3]);
/* x >= 0 rounded to a float no larger: a head's radius or slack unit the list may trust. */
static inline float nodelist_float_below(double x)
{
  float f = (float)x;
  if ((double)f > x) { /* the next float down: f > 0, one less in its bits */
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    u--;
    memcpy(&f, &u, sizeof f);
  }
  return f;
}

/* The per-node steps are inline: they run for every looked-up node. */

/* A left-out node (or cluster) that must move by d to touch B: the list holds until d. */
static inline void nodelist_margin(node_list *L, double d)
{
  L->margin = d < L->margin ? d : L->margin;
}

/* The slack of a node listed at phi (lsdem_contact.h): min(phi / L, the bound's limit)
 * in slack units, rounded down; 0 when it may touch or there is no bound. */
static inline unsigned nodelist_slack(const node_list *L, double phi)
{
  const double above = phi > 0.0 ? phi * L->inv_lip : 0.0;
  const double units = (above < L->cap ? above : L->cap) * L->slack_per_length;
  return (unsigned)(units < 31.0 ? units : 31.0);
}

/* Whether a listed node's lookup is skipped: the motion since the list's build has not
 * used up the node's slack. */
static inline int nodelist_skips(const node_list *L, const lsdem_nodelist_entry *e)
{
  return e->slack && L->moved < e->slack * L->slack_unit;
}

/* Entry e of the output list: node k at x (A's frame) with its cell c and slack. */
static inline void nodelist_write(const node_list *L, lsdem_nodelist_entry *e, int k,
                                  const double x[3], const lsdem_grid_cell *c, unsigned slack)
{
  const int samples = L->out->head->cells;
  const int kept = samples && c && c->index >= 0 && c->index <= INT32_MAX;
  e->node = (uint32_t)k;
  e->slack = slack;
  e->cell = kept ? (int32_t)c->index : -1;
  memcpy(lsdem_nodelist_x(e), x, 3 * sizeof(double));
  if (kept)
    memcpy(lsdem_nodelist_samples(e), c->v, sizeof c->v);
  else if (samples)
    memset(lsdem_nodelist_samples(e), 0, sizeof c->v);
}

/* The place of the output list's next entry (entries stay in increasing node order). */
static inline lsdem_nodelist_entry *nodelist_next(const node_list *L)
{
  lsdem_nodelist_head *h = L->out->head;
  lsdem_nodelist_entry *e = L->out->entry + h->words;
  h->words += lsdem_nodelist_entry_words(h);
  h->count++;
  return e;
}

/* The cell kept in an entry (cell -1: none; an entry without samples keeps none). */
static inline void nodelist_entry_cell(const lsdem_nodelist_entry *e, lsdem_grid_cell *c)
{
  c->index = e->cell;
  if (e->cell >= 0) memcpy(c->v, lsdem_nodelist_samples(e), sizeof c->v);
}

/* The cell the input list kept for node k (nodes asked in increasing order), or none. */
static inline void nodelist_cell_of(node_list *L, int k, lsdem_grid_cell *c)
{
  c->index = -1;
  if (L->node_cursor >= L->nnode_in) return;
  const int words = lsdem_nodelist_entry_words(L->head_in);
  const lsdem_nodelist_entry *e = L->node_in + (size_t)L->node_cursor * words;
  for (; L->node_cursor < L->nnode_in && (int)e->node < k; e += words) L->node_cursor++;
  if (L->node_cursor < L->nnode_in && (int)e->node == k) nodelist_entry_cell(e, c);
}

/* Finishes the output list (its validity radius when built, its node count). */
void nodelist_finish(node_list *L);

#endif /* LSDEM_CONTACT_NODELIST_H */
