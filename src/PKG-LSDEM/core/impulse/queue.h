/* queue.h -- the ETM's priority queues (internal to core/impulse): an indexed binary
 * min-heap over contact indices 0..n-1 with keys that change in place.
 *
 * Order: (key, index) lexicographically, a strict total order, so the top and every
 * group collected below a threshold are the same whatever the history of pushes and
 * updates: ties are broken by the contacts' caller-given order (determinism).
 * Storage is the caller's: heap[n], pos[n] (pos[c] = -1: c not queued), key[n]. */
#ifndef LSDEM_IMPULSE_QUEUE_H
#define LSDEM_IMPULSE_QUEUE_H

#include <stdint.h>

typedef struct {
  int32_t n;     /* queued contacts */
  int32_t *heap; /* heap[0] is the top */
  int32_t *pos;  /* position of each contact in heap, -1 if not queued */
  double *key;   /* each contact's key */
} lsdem_etm_queue;

/* An empty queue over storage for cap contacts (pos all -1). */
void lsdem_etm_queue_init(lsdem_etm_queue *q, int32_t cap, int32_t *heap, int32_t *pos,
                          double *key);
/* Queue c with key k, or move it to key k if queued. */
void lsdem_etm_queue_set(lsdem_etm_queue *q, int32_t c, double k);
/* Take c out (nothing if not queued). */
void lsdem_etm_queue_remove(lsdem_etm_queue *q, int32_t c);
/* Every queued contact with key <= limit, into out (room for q->n), in the order a walk
 * of the heap from its top meets them -- a function of the keys and of the sequence of
 * pushes and updates alone, so of the contact order and not of the bodies' (no sort: no
 * allocation); returns the count. stack holds q->n entries. */
int32_t lsdem_etm_queue_collect(const lsdem_etm_queue *q, double limit, int32_t *out,
                                int32_t *stack);
/* Invariants (heap order, pos consistent): 1 if they hold. */
int lsdem_etm_queue_valid(const lsdem_etm_queue *q, int32_t cap);

#endif
