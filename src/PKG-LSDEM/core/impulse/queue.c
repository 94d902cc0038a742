/* queue.c -- the ETM's indexed min-heap (queue.h). */
#include "queue.h"

/* a before b in (key, index) order */
static int before(const lsdem_etm_queue *q, int32_t a, int32_t b)
{
  return q->key[a] < q->key[b] || (q->key[a] == q->key[b] && a < b);
}

static void place(lsdem_etm_queue *q, int32_t at, int32_t c)
{
  q->heap[at] = c;
  q->pos[c] = at;
}

static void sift_up(lsdem_etm_queue *q, int32_t at)
{
  const int32_t c = q->heap[at];
  while (at > 0) {
    const int32_t up = (at - 1) / 2;
    if (!before(q, c, q->heap[up])) break;
    place(q, at, q->heap[up]);
    at = up;
  }
  place(q, at, c);
}

static void sift_down(lsdem_etm_queue *q, int32_t at)
{
  const int32_t c = q->heap[at];
  for (;;) {
    int32_t child = 2 * at + 1;
    if (child >= q->n) break;
    if (child + 1 < q->n && before(q, q->heap[child + 1], q->heap[child])) child++;
    if (!before(q, q->heap[child], c)) break;
    place(q, at, q->heap[child]);
    at = child;
  }
  place(q, at, c);
}

void lsdem_etm_queue_init(lsdem_etm_queue *q, int32_t cap, int32_t *heap, int32_t *pos,
                          double *key)
{
  q->n = 0;
  q->heap = heap;
  q->pos = pos;
  q->key = key;
  for (int32_t c = 0; c < cap; c++) pos[c] = -1;
}

void lsdem_etm_queue_set(lsdem_etm_queue *q, int32_t c, double k)
{
  if (q->pos[c] < 0) {
    q->key[c] = k;
    place(q, q->n++, c);
    sift_up(q, q->n - 1);
    return;
  }
  const double old = q->key[c];
  q->key[c] = k;
  if (k < old)
    sift_up(q, q->pos[c]);
  else
    sift_down(q, q->pos[c]);
}

void lsdem_etm_queue_remove(lsdem_etm_queue *q, int32_t c)
{
  const int32_t at = q->pos[c];
  if (at < 0) return;
  q->pos[c] = -1;
  const int32_t last = q->heap[--q->n];
  if (at == q->n) return;
  place(q, at, last);
  sift_down(q, at);
  sift_up(q, q->pos[last]);
}

/* A subtree whose root's key is above the limit holds nothing below it (heap order). */
int32_t lsdem_etm_queue_collect(const lsdem_etm_queue *q, double limit, int32_t *out,
                                int32_t *stack)
{
  int32_t nout = 0, top = 0;
  if (q->n > 0) stack[top++] = 0;
  while (top > 0) {
    const int32_t at = stack[--top];
    const int32_t c = q->heap[at];
    if (!(q->key[c] <= limit)) continue;
    out[nout++] = c;
    for (int32_t child = 2 * at + 1; child <= 2 * at + 2 && child < q->n; child++)
      stack[top++] = child;
  }
  return nout;
}

int lsdem_etm_queue_valid(const lsdem_etm_queue *q, int32_t cap)
{
  int32_t queued = 0;
  for (int32_t c = 0; c < cap; c++) {
    if (q->pos[c] < 0) continue;
    queued++;
    if (q->pos[c] >= q->n || q->heap[q->pos[c]] != c) return 0;
  }
  if (queued != q->n) return 0;
  for (int32_t at = 1; at < q->n; at++)
    if (before(q, q->heap[at], q->heap[(at - 1) / 2])) return 0;
  return 1;
}
