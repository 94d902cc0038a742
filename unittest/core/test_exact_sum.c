/* test_exact_sum.c -- order-free sums (lsdem_quantum_for, lsdem_quantize): terms rounded
 * to the quantum sum to the same bits in any order (the same contact forces summed in
 * another rank count's order), while the same terms unrounded do not; the rounding is
 * to the nearest multiple (error <= q/2, ties to even), the quantum is the power of two
 * that keeps 40 bits below the scale, and no quantum leaves terms unchanged. */
#include "lsdem_test.h"

#include <float.h>
#include <math.h>
#include <string.h>

enum { NTERMS = 64, ORDERS = 200 };

static void shuffle(int *idx, int n)
{
  for (int i = n - 1; i > 0; i--) {
    const int j = (int)(urand() * (i + 1)) % (i + 1);
    const int t = idx[i];
    idx[i] = idx[j];
    idx[j] = t;
  }
}

static double sum_in_order(const double *x, const int *idx, int n)
{
  double s = 0.0;
  for (int k = 0; k < n; k++) s += x[idx[k]];
  return s;
}

/* lsdem_quantize3_scaled (two components at a time where SSE2 is there) gives the bits of
 * lsdem_quantize_on on each scaled component: random terms, ties, signed zeros, terms at
 * and beyond the exact range, infinities and NaN, out aliasing v; no quantum: s v. */
static void test_vector_rounding(lsdem_quantum qt)
{
  const double special[] = {0.0, -0.0, 2.5, -3.5, 0x1p51, -0x1p51, 0x1.fffffffffffffp50,
                            0x1p60, HUGE_VAL, -HUGE_VAL, NAN, 1e-300};
  const int nspecial = (int)(sizeof special / sizeof special[0]);
  int same = 1, trials = 0;
  for (int t = 0; t < 3000; t++) {
    double v[3], s = t % 5 ? srand1() * 3.0 : 1.0;
    for (int i = 0; i < 3; i++)
      v[i] = t % 4 == 0 ? special[(t / 4 + 5 * i) % nspecial] * qt.q
                        : srand1() * pow(10.0, 4.0 * srand1());
    for (int scaled_by_none = 0; scaled_by_none < 2; scaled_by_none++) {
      const lsdem_quantum use = scaled_by_none ? lsdem_quantum_for(0.0) : qt;
      double want[3], got[3], in_place[3];
      for (int i = 0; i < 3; i++)
        want[i] = use.q > 0.0 ? lsdem_quantize_on(s * v[i], use) : s * v[i];
      lsdem_quantize3_scaled(s, v, use, got);
      memcpy(in_place, v, sizeof v);
      lsdem_quantize3_scaled(s, in_place, use, in_place);
      for (int i = 0; i < 3; i++) /* NaN: any NaN */
        if (!(isnan(want[i]) ? isnan(got[i]) && isnan(in_place[i])
                             : memcmp(&want[i], &got[i], sizeof(double)) == 0 &&
                                   memcmp(&want[i], &in_place[i], sizeof(double)) == 0)) {
          same = 0;
          CHECK(0, "trial %d: component %d of s v = %.17g: %.17g, not %.17g", t, i, s * v[i],
                got[i], want[i]);
        }
      trials++;
    }
  }
  CHECK(same && trials == 6000, "lsdem_quantize3_scaled differs from lsdem_quantize_on");
}

int main(void)
{
  /* the quantum of a scale */
  const double scales[] = {1.0, 3.0, 1e-7, 12345.678, 0x1p30};
  for (int k = 0; k < 5; k++) {
    const lsdem_quantum qt = lsdem_quantum_for(scales[k]);
    const double top = qt.q * 0x1p40;
    CHECK(top > scales[k] && top <= 2.0 * scales[k] && qt.q * qt.inv_q == 1.0 &&
              frexp(qt.q, &(int){0}) == 0.5,
          "scale %g: q %g", scales[k], qt.q);
  }
  const lsdem_quantum none = lsdem_quantum_for(0.0);
  CHECK(none.q == 0.0 && lsdem_quantize(0.123456789, none) == 0.123456789 &&
            lsdem_quantum_for(HUGE_VAL).q == 0.0 && lsdem_quantum_for(NAN).q == 0.0,
        "no quantum changes terms");

  /* contact-force-like terms: a few large, many small, both signs */
  const lsdem_quantum qt = lsdem_quantum_for(1000.0);
  double raw[NTERMS], q[NTERMS];
  int worst_ok = 1;
  for (int k = 0; k < NTERMS; k++) {
    raw[k] = srand1() * pow(10.0, 3.0 * srand1()) * (k % 7 == 0 ? 1.0 : 1e-3);
    q[k] = lsdem_quantize(raw[k], qt);
    worst_ok &= fabs(q[k] - raw[k]) <= 0.5 * qt.q && fmod(q[k], qt.q) == 0.0;
  }
  CHECK(worst_ok, "rounding is to the nearest multiple of q");
  CHECK(lsdem_quantize(2.5 * qt.q, qt) == 2.0 * qt.q &&
            lsdem_quantize(3.5 * qt.q, qt) == 4.0 * qt.q &&
            lsdem_quantize(-2.5 * qt.q, qt) == -2.0 * qt.q,
        "ties go to even");
  int idx[NTERMS];
  for (int k = 0; k < NTERMS; k++) idx[k] = k;
  const double ref_q = sum_in_order(q, idx, NTERMS), ref_raw = sum_in_order(raw, idx, NTERMS);
  int same_q = 1, same_raw = 1;
  for (int o = 0; o < ORDERS; o++) {
    shuffle(idx, NTERMS);
    same_q &= sum_in_order(q, idx, NTERMS) == ref_q;
    same_raw &= sum_in_order(raw, idx, NTERMS) == ref_raw;
  }
  CHECK(same_q, "rounded terms: the sum depends on the order");
  CHECK(!same_raw, "unrounded terms summed the same in %d orders: the test shows nothing",
        ORDERS);
  /* the rounded sum is the unrounded one to within n q / 2 */
  CHECK(fabs(ref_q - ref_raw) <= NTERMS * 0.5 * qt.q, "sum moved by %g", ref_q - ref_raw);
  /* beyond the exact range a term passes unchanged */
  CHECK(lsdem_quantize(0x1p52 * qt.q, qt) == 0x1p52 * qt.q && isnan(lsdem_quantize(NAN, qt)),
        "out-of-range terms");
  test_vector_rounding(qt);
  return lsdem_test_summary();
}
