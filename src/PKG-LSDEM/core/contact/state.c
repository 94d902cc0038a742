/* state.c -- a pair's contact state (node list and shear history) as fixed-size records
 * for exchange between ranks and restart files, in the layout of every earlier version
 * (lsdem_contact.h), so that their restart files still load. */
#include "lsdem_contact.h"

#include <string.h>

/* record ids: the list head's two records, and node records at LIST_NODE + node */
enum { HEAD_POSE = -2, HEAD_COUNT = -1 };
#define LIST_NODE (-(1 << 29))

_Static_assert(sizeof(((lsdem_nodelist_entry *)0)->v) ==
                   sizeof(((lsdem_state_record *)0)->stamp) +
                       sizeof(((lsdem_state_record *)0)->a),
               "a node record holds a cell's 8 samples in its stamp and a");

_Static_assert(sizeof(lsdem_nodelist_entry) == 64, "a node-list entry fills one 64-byte slot");
_Static_assert(LSDEM_LIBRARY_MAX_NODES < LSDEM_NODELIST_NO_NODE, "node indices fit an entry");

static int is_node_record(int32_t id, int nnodes)
{
  return id >= LIST_NODE && id < LIST_NODE + nnodes;
}

int lsdem_pair_state_records(const lsdem_pair_state *st)
{
  return (st->list.valid ? 2 + st->list.head->count : 0) + st->nshear;
}

static void encode_head(const lsdem_nodelist_head *h, lsdem_state_record *rec)
{
  lsdem_state_record *pose = &rec[0], *count = &rec[1];
  pose->id = HEAD_POSE;
  pose->aux = h->stride;
  pose->stamp = h->built;
  count->id = HEAD_COUNT;
  count->aux = h->count;
  memcpy(&count->stamp, &h->radius, sizeof count->stamp);
  for (int i = 0; i < 3; i++) {
    pose->a[i] = h->M[i];
    pose->b[i] = h->M[3 + i];
    count->a[i] = h->M[6 + i];
    count->b[i] = h->t[i];
  }
}

static void decode_head(const lsdem_state_record *rec, lsdem_nodelist_head *h)
{
  h->stride = rec[0].aux;
  h->built = rec[0].stamp;
  h->count = rec[1].aux;
  h->slack_unit = 0.0; /* not in the records: no lookups skipped till the next build */
  memcpy(&h->radius, &rec[1].stamp, sizeof h->radius);
  for (int i = 0; i < 3; i++) {
    h->M[i] = rec[0].a[i];
    h->M[3 + i] = rec[0].b[i];
    h->M[6 + i] = rec[1].a[i];
    h->t[i] = rec[1].b[i];
  }
}

int lsdem_pair_state_encode(const lsdem_pair_state *st, lsdem_state_record *rec)
{
  int n = 0;
  if (st->list.valid) {
    encode_head(st->list.head, rec);
    n = 2;
    for (int k = 0; k < st->list.head->count; k++, n++) {
      const lsdem_nodelist_entry *e = &st->list.entry[k];
      lsdem_state_record *r = &rec[n];
      r->id = LIST_NODE + e->node;
      r->aux = e->cell;
      memcpy(&r->stamp, e->v, sizeof e->v); /* stamp and a, 32 bytes */
      memcpy(r->b, e->x, sizeof r->b);
    }
  }
  for (int k = 0; k < st->nshear; k++, n++) {
    const lsdem_shear_hist *h = &st->shear[k];
    lsdem_state_record *r = &rec[n];
    r->id = h->node;
    r->aux = h->pad_;
    r->stamp = h->stamp;
    memcpy(r->a, h->shear, sizeof r->a);
    memcpy(r->b, h->normal, sizeof r->b);
  }
  return n;
}

/* The list of rec, when it is one: a head, its count within n, its node records
 * following (the first one tells this layout from an older one); returns the records it
 * takes (0: none). */
static int decode_list(const lsdem_state_record *rec, int n, int nnodes, lsdem_nodelist *list)
{
  list->valid = 0;
  if (n < 2 || rec[0].id != HEAD_POSE || rec[1].id != HEAD_COUNT) return 0;
  const int count = rec[1].aux;
  if (count < 0 || count > n - 2 || (count > 0 && !is_node_record(rec[2].id, nnodes)))
    return 0;
  decode_head(rec, list->head);
  for (int k = 0; k < count; k++) {
    const lsdem_state_record *r = &rec[2 + k];
    lsdem_nodelist_entry *e = &list->entry[k];
    e->node = is_node_record(r->id, nnodes) ? (uint32_t)(r->id - LIST_NODE)
                                            : LSDEM_NODELIST_NO_NODE; /* dropped */
    e->slack = 0;
    e->cell = r->aux;
    memcpy(e->v, &r->stamp, sizeof e->v);
    memcpy(e->x, r->b, sizeof e->x);
  }
  list->valid = 1;
  return 2 + count;
}

void lsdem_pair_state_decode(const lsdem_state_record *rec, int n, int nnodes,
                             lsdem_pair_state *st)
{
  const int first = decode_list(rec, n, nnodes, &st->list);
  st->nshear = 0;
  for (int k = first; k < n; k++) {
    const lsdem_state_record *r = &rec[k];
    if (r->id < 0 || (st->nshear > 0 && r->id <= st->shear[st->nshear - 1].node)) continue;
    lsdem_shear_hist *h = &st->shear[st->nshear++];
    h->node = r->id;
    h->pad_ = r->aux;
    h->stamp = r->stamp;
    memcpy(h->shear, r->a, sizeof h->shear);
    memcpy(h->normal, r->b, sizeof h->normal);
  }
}
