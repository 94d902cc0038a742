/* state.c -- a pair's contact state (node list and shear history) as fixed-size records
 * for exchange between ranks and restart files, in the layout of every earlier version
 * (lsdem_contact.h), so that their restart files still load. */
#include "nodelist.h"

#include <string.h>

/* record ids: the list head's two records, and node records at LIST_NODE + node */
enum { HEAD_POSE = -2, HEAD_COUNT = -1 };
#define LIST_NODE (-(1 << 29))

_Static_assert(LSDEM_NODELIST_SAMPLE_WORDS * 8 ==
                   sizeof(((lsdem_state_record *)0)->stamp) +
                       sizeof(((lsdem_state_record *)0)->a),
               "a node record holds a cell's 8 samples in its stamp and a");
_Static_assert(sizeof(lsdem_nodelist_entry) == 8, "a node-list entry is one word");
_Static_assert(sizeof(lsdem_nodelist_head) % 8 == 0, "a list head is whole words");
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
  const double radius = h->radius;
  memcpy(&count->stamp, &radius, sizeof count->stamp);
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
  h->slack_unit = 0.0f; /* not in the records: no lookups skipped till the next build */
  double radius;
  memcpy(&radius, &rec[1].stamp, sizeof radius);
  h->radius = nodelist_float_below(radius); /* an earlier version's double */
  for (int i = 0; i < 3; i++) { /* rounded to float, as when built */
    h->M[i] = (float)rec[0].a[i];
    h->M[3 + i] = (float)rec[0].b[i];
    h->M[6 + i] = (float)rec[1].a[i];
    h->t[i] = (float)rec[1].b[i];
  }
}

int lsdem_pair_state_encode(const lsdem_pair_state *st, lsdem_state_record *rec)
{
  int n = 0;
  if (st->list.valid) {
    const lsdem_nodelist_head *h = st->list.head;
    encode_head(h, rec);
    n = 2;
    const int words = lsdem_nodelist_entry_words(h);
    const lsdem_nodelist_entry *e = st->list.entry;
    for (int k = 0; k < h->count; k++, n++, e += words) {
      lsdem_state_record *r = &rec[n];
      r->id = LIST_NODE + e->node;
      r->aux = e->cell; /* -1 in a list without cells */
      if (h->cells) /* stamp and a, 32 bytes */
        memcpy(&r->stamp, lsdem_nodelist_samples(e), 8 * LSDEM_NODELIST_SAMPLE_WORDS);
      else
        memset(&r->stamp, 0, 8 * LSDEM_NODELIST_SAMPLE_WORDS);
      memcpy(r->b, lsdem_nodelist_x(e), sizeof r->b);
    }
  }
  for (int k = 0; k < st->nshear; k++, n++) {
    const lsdem_shear_hist *h = &st->shear[k];
    lsdem_state_record *r = &rec[n];
    r->id = h->node;
    r->aux = 0;
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
  list->head->cells = 0; /* the records' kept cells are carried (none: no samples) */
  for (int k = 0; k < count; k++) list->head->cells |= rec[2 + k].aux >= 0;
  const int words = lsdem_nodelist_entry_words(list->head);
  list->head->words = count * words;
  lsdem_nodelist_entry *e = list->entry;
  for (int k = 0; k < count; k++, e += words) {
    const lsdem_state_record *r = &rec[2 + k];
    e->node = is_node_record(r->id, nnodes) ? (uint32_t)(r->id - LIST_NODE)
                                            : LSDEM_NODELIST_NO_NODE; /* dropped */
    e->slack = 0;
    e->cell = list->head->cells && r->aux >= 0 ? r->aux : -1;
    memcpy(lsdem_nodelist_x(e), r->b, 3 * sizeof(double));
    if (list->head->cells)
      memcpy(lsdem_nodelist_samples(e), &r->stamp, 8 * LSDEM_NODELIST_SAMPLE_WORDS);
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
    h->stamp = lsdem_shear_stamp(r->stamp);
    memcpy(h->shear, r->a, sizeof h->shear);
    memcpy(h->normal, r->b, sizeof h->normal);
  }
}
