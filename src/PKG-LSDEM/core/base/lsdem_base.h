/* lsdem_base.h -- base of the LSDEM core: status codes and error messages, quaternions and 3x3 rotations.
 *
 * Part of the kernel (core/base). See lsdem.h for the conventions used throughout. */
#ifndef LSDEM_BASE_H
#define LSDEM_BASE_H

#include <stddef.h>
#include <stdint.h>

#include "lsdem_vec3.h" /* dot, cross, 3x3 products: inline, one copy */
#include "lsdem_quat.h" /* normalize, multiply, turn: inline, one copy */

#if defined(__SSE2__) /* every x86-64: the order-free sums' rounding two terms at a time */
#include <emmintrin.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- errors ---- */

typedef enum {
  LSDEM_OK = 0,
  LSDEM_ERR_ARG,     /* a bad argument (NULL, negative size, out of range) */
  LSDEM_ERR_IO,      /* a file could not be opened, read, written or mapped */
  LSDEM_ERR_FORMAT,  /* a file's content is malformed, truncated or corrupt */
  LSDEM_ERR_NOMEM,   /* an allocation failed or a size would overflow */
  LSDEM_ERR_NUMERIC  /* NaN/inf or a degenerate quantity (zero volume, ...) */
} lsdem_status;

typedef struct {
  char msg[512];
} lsdem_error;

/* Human-readable name of a status code ("format error", ...). */
const char *lsdem_status_name(lsdem_status s);

/* Record a printf-style message in err (if not NULL) and return s. */
lsdem_status lsdem_fail(lsdem_error *err, lsdem_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ------------------------------------------------- quaternions, rotations ---- */

void lsdem_quat_conjugate(const double q[4], double out[4]);
void lsdem_quat_to_matrix(const double q[4], double R[9]);          /* body -> world */
void lsdem_matrix_to_quat(const double R[9], double q[4]);          /* proper rotation */
void lsdem_quat_rotate(const double q[4], const double v[3], double out[3]);     /* R v */
void lsdem_quat_rotate_inv(const double q[4], const double v[3], double out[3]); /* R^T v */
/* q <- q * exp(omega_body * dt / 2): exact update for a body-frame angular velocity
 * held constant over dt (solution of the quaternion rate equation, report eq 2.28). */
void lsdem_quat_advance(double q[4], const double omega_body[3], double dt);
/* lsdem_quat_turn (lsdem_quat.h): q <- exp(omega * dt / 2) * q, the same update for a
 * world-frame angular velocity omega (= R omega_body), without taking omega to the body
 * frame. */
/* Rodrigues' formula (report eq 2.9): rotate v about the unit axis k by angle theta. */
void lsdem_rodrigues(const double v[3], const double k[3], double theta, double out[3]);
/* lsdem_rotate_between (lsdem_quat.h): rotate v by the rotation that takes unit vector
 * n_old onto unit vector n_new (the operator Z of report eq 2.8). Identity when
 * n_old == n_new. */

/* Kawamoto/Tan rotation files store (q0 q1 q2 q3) = their code's quaternion, w last.
 * Their rotation matrix (report eq 2.26 with Evans' q1..q4 = file q0..q3) equals the
 * textbook body->world matrix of the scalar-first quaternion (q3, -q1, q0, -q2). */
void lsdem_quat_from_tan(const double qtan[4], double q[4]);
void lsdem_quat_to_tan(const double q[4], double qtan[4]);
/* Eq 2.26 exactly as printed, with Evans' (q1, q2, q3, q4) = qtan[0..3]. */
void lsdem_tan_matrix_eq226(const double qtan[4], double R[9]);

/* ------------------------------------------------------- order-free sums ---- */

/* Sums whose value does not depend on the order of their terms (the same on any rank
 * count and after a restart): each term is rounded to a multiple of a power-of-two
 * quantum q (fixed-point arithmetic carried in doubles), so every partial sum of such
 * terms is exact, and therefore the same in any order, while it stays below 2^53 q. A
 * quantum is chosen for a scale F (the largest single term expected, e.g. the stiffest
 * contact spring times the largest grain radius) as the power of two
 * q = 2^(floor(log2 F) + 1 - LSDEM_EXACT_SUM_BITS): terms keep LSDEM_EXACT_SUM_BITS bits
 * below the power of two above F (a resolution under F / 2^39 ~ 2e-12 F), and sums stay
 * exact up to 2^12 F. */
#define LSDEM_EXACT_SUM_BITS 40
typedef struct {
  double q, inv_q; /* q = 0: no rounding (terms pass unchanged) */
} lsdem_quantum;
/* The quantum for terms of magnitude up to scale (scale <= 0 or not finite: none). */
lsdem_quantum lsdem_quantum_for(double scale);
/* x rounded to the nearest multiple of the quantum (ties to even), in exact arithmetic:
 * x / q and back are exact (powers of two), and adding and removing 1.5 * 2^52 rounds a
 * double below 2^51 to an integer in the default rounding mode (inline: it runs for every
 * contact). Terms beyond 2^51 q (and NaN) pass unchanged: far outside the exact range. */
static inline double lsdem_quantize_on(double x, lsdem_quantum qt) /* qt.q > 0 */
{
  const double y = x * qt.inv_q, round = 0x1.8p52;
  const double rounded = ((y + round) - round) * qt.q;
  return fabs(y) < 0x1p51 ? rounded : x; /* a select, not a branch */
}
static inline double lsdem_quantize(double x, lsdem_quantum qt)
{
  return qt.q > 0.0 ? lsdem_quantize_on(x, qt) : x;
}
#if defined(__SSE2__)
/* lsdem_quantize_on of both lanes of x, the same bits: the select as masks, so that the
 * compiler need not branch (it may not compute the rounding for a term that passes, when
 * floating-point traps are possible). */
static inline __m128d lsdem_quantize2_on(__m128d x, lsdem_quantum qt) /* qt.q > 0 */
{
  const __m128d round = _mm_set1_pd(0x1.8p52);
  const __m128d y = _mm_mul_pd(x, _mm_set1_pd(qt.inv_q));
  const __m128d rounded = _mm_mul_pd(_mm_sub_pd(_mm_add_pd(y, round), round), _mm_set1_pd(qt.q));
  const __m128d in_range = _mm_cmplt_pd(_mm_andnot_pd(_mm_set1_pd(-0.0), y), /* |y| < 2^51 */
                                        _mm_set1_pd(0x1p51));
  return _mm_or_pd(_mm_and_pd(in_range, rounded), _mm_andnot_pd(in_range, x));
}
#endif
/* The same for the three components of s v into out (out may alias v): one test of the
 * quantum for the three (every contact's force and torques; with SSE2 two components at a
 * time, the same bits). */
static inline void lsdem_quantize3_scaled(double s, const double v[3], lsdem_quantum qt,
                                          double out[3])
{
  if (!(qt.q > 0.0)) {
    for (int i = 0; i < 3; i++) out[i] = s * v[i];
    return;
  }
#if defined(__SSE2__)
  const __m128d sv = _mm_set1_pd(s);
  const __m128d xy = lsdem_quantize2_on(_mm_mul_pd(sv, _mm_loadu_pd(v)), qt);
  const __m128d z = lsdem_quantize2_on(_mm_mul_sd(sv, _mm_load_sd(v + 2)), qt);
  _mm_storeu_pd(out, xy);
  _mm_store_sd(out + 2, z);
#else
  for (int i = 0; i < 3; i++) out[i] = lsdem_quantize_on(s * v[i], qt);
#endif
}
static inline void lsdem_quantize3(const double v[3], lsdem_quantum qt, double out[3])
{
  lsdem_quantize3_scaled(1.0, v, qt, out);
}

/* Symmetric 3x3 eigen-decomposition (Jacobi). Eigenvalues ascending in w; column k of V
 * (V[3*i+k]) is the unit eigenvector of w[k]; V is a proper rotation (det +1). */
void lsdem_sym_eigen(const double A[9], double w[3], double V[9]);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_BASE_H */
