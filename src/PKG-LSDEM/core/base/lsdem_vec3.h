/* lsdem_vec3.h -- the one copy of the core's small vector and 3x3 matrix helpers, inline,
 * and the per-step paths' scalar max and min. Vectors are double[3]; matrices 3x3
 * row-major double[9]. Every function may be called with out aliasing an input (results
 * are formed before they are stored). */
#ifndef LSDEM_VEC3_H
#define LSDEM_VEC3_H

/* The larger (smaller) of a and b as a select, for the per-step paths: GCC calls libm's
 * fmax and fmin unless NaNs are ruled out, and every live floating-point register is
 * saved around such a call (2 calls per resting update, 6 per clamp of a point into a
 * grid's box). The same value as glibc's fmax(a, b) (fmin) whenever b is not a NaN,
 * signed zeros included (b when they compare equal); a NaN in a gives b. So the argument
 * that may be a NaN goes first. */
static inline double lsdem_max(double a, double b) { return a > b ? a : b; }
static inline double lsdem_min(double a, double b) { return a < b ? a : b; }

static inline double lsdem_dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* a x b */
static inline void lsdem_cross3(const double a[3], const double b[3], double out[3])
{
  const double x = a[1] * b[2] - a[2] * b[1];
  const double y = a[2] * b[0] - a[0] * b[2];
  const double z = a[0] * b[1] - a[1] * b[0];
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

/* a - b */
static inline void lsdem_sub3(const double a[3], const double b[3], double out[3])
{
  out[0] = a[0] - b[0];
  out[1] = a[1] - b[1];
  out[2] = a[2] - b[2];
}

/* R v */
static inline void lsdem_mat_vec(const double R[9], const double v[3], double out[3])
{
  const double x = R[0] * v[0] + R[1] * v[1] + R[2] * v[2];
  const double y = R[3] * v[0] + R[4] * v[1] + R[5] * v[2];
  const double z = R[6] * v[0] + R[7] * v[1] + R[8] * v[2];
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

/* R^T v */
static inline void lsdem_matT_vec(const double R[9], const double v[3], double out[3])
{
  const double x = R[0] * v[0] + R[3] * v[1] + R[6] * v[2];
  const double y = R[1] * v[0] + R[4] * v[1] + R[7] * v[2];
  const double z = R[2] * v[0] + R[5] * v[1] + R[8] * v[2];
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

/* M v + t */
static inline void lsdem_affine3(const double M[9], const double t[3], const double v[3],
                                 double out[3])
{
  const double x = M[0] * v[0] + M[1] * v[1] + M[2] * v[2] + t[0];
  const double y = M[3] * v[0] + M[4] * v[1] + M[5] * v[2] + t[1];
  const double z = M[6] * v[0] + M[7] * v[1] + M[8] * v[2] + t[2];
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

/* C = A B (C must not alias A or B) */
static inline void lsdem_mat_mul(const double A[9], const double B[9], double C[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

/* C = A^T B (C must not alias A or B) */
static inline void lsdem_matT_mul(const double A[9], const double B[9], double C[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      C[3 * i + j] = A[i] * B[j] + A[3 + i] * B[3 + j] + A[6 + i] * B[6 + j];
}

#endif /* LSDEM_VEC3_H */
