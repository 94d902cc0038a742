/* smooth.c -- convolution of field channels with the normalised Gaussian kernel: by FFTW
 * (cost independent of the kernel width) and by direct summation (lsdem_fields.h). */
#include "lsdem_fields.h"

#include <fftw3.h>
#include <stdlib.h>
#include <string.h>

/* kernel (real, periodic offsets) -> its half spectrum; plans on the given buffers */
typedef struct {
  double *real;
  fftw_complex *spectrum, *kernel_spectrum;
  fftw_plan forward, backward;
  size_t nodes, modes;
} fft_work;

static void fft_work_free(fft_work *w)
{
  if (w->forward) fftw_destroy_plan(w->forward);
  if (w->backward) fftw_destroy_plan(w->backward);
  fftw_free(w->real);
  fftw_free(w->spectrum);
  fftw_free(w->kernel_spectrum);
}

/* FFTW's arrays are row-major with the LAST index fastest: our x-fastest layout is
 * FFTW's (n2, n1, n0) */
static int fft_work_init(const lsdem_field_grid *g, double width, fft_work *w)
{
  memset(w, 0, sizeof *w);
  w->nodes = lsdem_field_grid_nodes(g);
  w->modes = (size_t)g->n[2] * (size_t)g->n[1] * (size_t)(g->n[0] / 2 + 1);
  w->real = fftw_malloc(w->nodes * sizeof(double));
  w->spectrum = fftw_malloc(w->modes * sizeof(fftw_complex));
  w->kernel_spectrum = fftw_malloc(w->modes * sizeof(fftw_complex));
  if (!w->real || !w->spectrum || !w->kernel_spectrum) return 0;
  w->forward = fftw_plan_dft_r2c_3d(g->n[2], g->n[1], g->n[0], w->real, w->spectrum,
                                    FFTW_ESTIMATE);
  w->backward = fftw_plan_dft_c2r_3d(g->n[2], g->n[1], g->n[0], w->spectrum, w->real,
                                     FFTW_ESTIMATE);
  if (!w->forward || !w->backward) return 0;
  lsdem_field_kernel(g, width, w->real);
  fftw_execute(w->forward);
  /* the inverse transform is unnormalised: fold 1/N into the kernel's spectrum */
  const double scale = 1.0 / (double)w->nodes;
  for (size_t k = 0; k < w->modes; k++) {
    w->kernel_spectrum[k][0] = scale * w->spectrum[k][0];
    w->kernel_spectrum[k][1] = scale * w->spectrum[k][1];
  }
  return 1;
}

static void convolve_channel(fft_work *w, double *channel)
{
  memcpy(w->real, channel, w->nodes * sizeof(double));
  fftw_execute(w->forward);
  for (size_t k = 0; k < w->modes; k++) {
    const double a = w->spectrum[k][0], b = w->spectrum[k][1];
    const double c = w->kernel_spectrum[k][0], d = w->kernel_spectrum[k][1];
    w->spectrum[k][0] = a * c - b * d;
    w->spectrum[k][1] = a * d + b * c;
  }
  fftw_execute(w->backward); /* c2r overwrites its input: spectrum is scratch */
  memcpy(channel, w->real, w->nodes * sizeof(double));
}

lsdem_status lsdem_field_smooth_fft(const lsdem_field_grid *g, double width, int nchan,
                                    double *channels, lsdem_error *err)
{
  fft_work w;
  if (!fft_work_init(g, width, &w)) {
    fft_work_free(&w);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "field smoothing: no memory for a %dx%dx%d FFT",
                      g->n[0], g->n[1], g->n[2]);
  }
  for (int c = 0; c < nchan; c++) convolve_channel(&w, channels + (size_t)c * w.nodes);
  fft_work_free(&w);
  return LSDEM_OK;
}

/* node index j + o on axis k: wrapped on a periodic axis (the open axes' padding keeps it
 * inside) */
static size_t axis_index(const lsdem_field_grid *g, int k, int i)
{
  if (g->periodic[k]) i = ((i % g->n[k]) + g->n[k]) % g->n[k];
  return (size_t)i;
}

/* out[j + o] += kernel[o] in[j] for every node j holding a deposit and every offset o
 * within reach: the cost is the occupied nodes times the kernel's (2 reach + 1)^3, the
 * way a direct sum over grains goes */
static void convolve_direct(const lsdem_field_grid *g, const int reach[3],
                            const double *kernel, const double *in, double *out)
{
  const int *n = g->n;
  const size_t nodes = lsdem_field_grid_nodes(g);
  memset(out, 0, nodes * sizeof(double));
  size_t node = 0;
  for (int j2 = 0; j2 < n[2]; j2++)
    for (int j1 = 0; j1 < n[1]; j1++)
      for (int j0 = 0; j0 < n[0]; j0++, node++) {
        if (in[node] == 0.0) continue;
        for (int o2 = -reach[2]; o2 <= reach[2]; o2++)
          for (int o1 = -reach[1]; o1 <= reach[1]; o1++) {
            const size_t row = (size_t)n[0] * (axis_index(g, 1, j1 + o1) +
                                               (size_t)n[1] * axis_index(g, 2, j2 + o2));
            const size_t krow = (size_t)n[0] * ((size_t)(o1 < 0 ? o1 + n[1] : o1) +
                                                (size_t)n[1] * (size_t)(o2 < 0 ? o2 + n[2] : o2));
            for (int o0 = -reach[0]; o0 <= reach[0]; o0++)
              out[row + axis_index(g, 0, j0 + o0)] +=
                  kernel[krow + (size_t)(o0 < 0 ? o0 + n[0] : o0)] * in[node];
          }
      }
}

lsdem_status lsdem_field_smooth_direct(const lsdem_field_grid *g, double width, int nchan,
                                       double *channels, lsdem_error *err)
{
  const size_t nodes = lsdem_field_grid_nodes(g);
  double *kernel = malloc(nodes * sizeof(double));
  double *in = malloc(nodes * sizeof(double));
  if (!kernel || !in) {
    free(kernel);
    free(in);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "field smoothing: no memory for %zu nodes", nodes);
  }
  lsdem_field_kernel(g, width, kernel);
  int reach[3];
  for (int k = 0; k < 3; k++) {
    reach[k] = lsdem_field_grid_reach(g, width, k);
    if (2 * reach[k] + 1 > g->n[k]) reach[k] = (g->n[k] - 1) / 2; /* the kernel is zero beyond */
  }
  for (int c = 0; c < nchan; c++) {
    double *channel = channels + (size_t)c * nodes;
    memcpy(in, channel, nodes * sizeof(double));
    convolve_direct(g, reach, kernel, in, channel);
  }
  free(kernel);
  free(in);
  return LSDEM_OK;
}

lsdem_status lsdem_field_smooth_terms(const lsdem_field_grid *g, double width, int nin,
                                      const double *in, int nout, double *out, int nterms,
                                      const lsdem_field_term *terms, lsdem_error *err)
{
  fft_work w;
  memset(&w, 0, sizeof w);
  w.nodes = lsdem_field_grid_nodes(g);
  w.modes = (size_t)g->n[2] * (size_t)g->n[1] * (size_t)(g->n[0] / 2 + 1);
  fftw_complex *kspec[LSDEM_FIELD_KERNELS] = {NULL};
  w.real = fftw_malloc(w.nodes * sizeof(double));
  w.spectrum = fftw_malloc(w.modes * sizeof(fftw_complex));
  fftw_complex *ins = fftw_malloc((size_t)nin * w.modes * sizeof(fftw_complex));
  int ok = w.real && w.spectrum && ins;
  if (ok) {
    w.forward = fftw_plan_dft_r2c_3d(g->n[2], g->n[1], g->n[0], w.real, w.spectrum,
                                     FFTW_ESTIMATE);
    w.backward = fftw_plan_dft_c2r_3d(g->n[2], g->n[1], g->n[0], w.spectrum, w.real,
                                      FFTW_ESTIMATE);
    ok = w.forward && w.backward;
  }
  /* the kernels the terms use, each spectrum scaled by 1/N (the inverse is unnormalised) */
  const double scale = 1.0 / (double)w.nodes;
  for (int t = 0; ok && t < nterms; t++) {
    const int k = terms[t].kernel;
    if (kspec[k]) continue;
    if (!(kspec[k] = fftw_malloc(w.modes * sizeof(fftw_complex)))) {
      ok = 0;
      break;
    }
    lsdem_field_kernel_moment(g, width, k, w.real);
    fftw_execute(w.forward);
    for (size_t m = 0; m < w.modes; m++) {
      kspec[k][m][0] = scale * w.spectrum[m][0];
      kspec[k][m][1] = scale * w.spectrum[m][1];
    }
  }
  for (int c = 0; ok && c < nin; c++) {
    memcpy(w.real, in + (size_t)c * w.nodes, w.nodes * sizeof(double));
    fftw_execute(w.forward);
    memcpy(ins + (size_t)c * w.modes, w.spectrum, w.modes * sizeof(fftw_complex));
  }
  for (int o = 0; ok && o < nout; o++) {
    memset(w.spectrum, 0, w.modes * sizeof(fftw_complex));
    for (int t = 0; t < nterms; t++) {
      if (terms[t].out != o) continue;
      const fftw_complex *a = ins + (size_t)terms[t].in * w.modes, *b = kspec[terms[t].kernel];
      for (size_t m = 0; m < w.modes; m++) {
        w.spectrum[m][0] += a[m][0] * b[m][0] - a[m][1] * b[m][1];
        w.spectrum[m][1] += a[m][0] * b[m][1] + a[m][1] * b[m][0];
      }
    }
    fftw_execute(w.backward);
    memcpy(out + (size_t)o * w.nodes, w.real, w.nodes * sizeof(double));
  }
  for (int k = 0; k < LSDEM_FIELD_KERNELS; k++) fftw_free(kspec[k]);
  fftw_free(ins);
  fft_work_free(&w);
  if (!ok)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "field smoothing: no memory for a %dx%dx%d FFT "
                      "of %d channels", g->n[0], g->n[1], g->n[2], nin);
  return LSDEM_OK;
}
