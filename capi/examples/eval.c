/* scratchwave from C: a Velinov material with two scratches, a batch of queries through
 * sw_eval, sw_pdf and sw_sample, and a rejected material. Prints every result as a hex
 * float (exact), one "name index value" per line; capi/tests/c_example.rs compiles this
 * file, runs it and compares each value with the Rust results bit for bit.
 *
 * Build (after `cargo build --release -p scratchwave-capi`):
 *   cc -O2 -Icapi/include capi/examples/eval.c target/release/libscratchwave_capi.a \
 *      -lpthread -ldl -lm -o eval && ./eval
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scratchwave.h"

#define N 64

static int fail(const char *what, SwStatus s) {
  fprintf(stderr, "%s failed (status %d): %s\n", what, (int)s, sw_last_error());
  return 1;
}

int main(void) {
  const char *material =
      "{\"model\": \"velinov\", \"sigma_um\": 10, \"material\": {\"F\": 0.9},"
      " \"scratches\": [{\"p0\": [-100, 0], \"p1\": [100, 0], \"width\": 2, \"depth\": 0.3},"
      "                 {\"p0\": [0, -80], \"p1\": [5, 80], \"width\": 1.5, \"depth\": 0.2,"
      "                  \"profile\": \"triangle\"}]}";
  SwBsdf *bsdf = NULL;
  SwStatus s = sw_bsdf_from_json(material, NULL, NULL, &bsdf);
  if (s != SW_STATUS_OK) return fail("sw_bsdf_from_json", s);
  printf("scratch_count 0 %zu\n", sw_bsdf_scratch_count(bsdf));

  /* Directions on a grid around the mirror direction, positions along the first scratch. */
  float wo[3 * N], wi[3 * N], x[2 * N], u[3 * N];
  for (int i = 0; i < N; i++) {
    float a = 0.05f * (float)(i % 8) - 0.2f, b = 0.04f * (float)(i / 8) - 0.15f;
    float o[3] = {0.3f, 0.1f, 0.0f}, l[3] = {-0.3f + a, -0.1f + b, 0.0f};
    o[2] = sqrtf(1.0f - o[0] * o[0] - o[1] * o[1]);
    l[2] = sqrtf(1.0f - l[0] * l[0] - l[1] * l[1]);
    for (int k = 0; k < 3; k++) {
      wo[3 * i + k] = o[k];
      wi[3 * i + k] = l[k];
    }
    x[2 * i] = 2.0f * (float)i - 64.0f;
    x[2 * i + 1] = 0.25f * (float)(i % 5);
    u[3 * i] = (float)((i * 37) % N) / N;
    u[3 * i + 1] = (float)((i * 11) % N) / N + 0.5f / N;
    u[3 * i + 2] = (float)((i * 23) % N) / N + 0.25f / N;
  }
  SwQueries q = {N, wo, wi, x, NULL, NULL, 0, 0}; /* RGB: 700, 520, 440 nm */
  float f[3 * N], pdf[N], swi[3 * N], sweight[3 * N], spdf[N];
  if ((s = sw_eval(bsdf, &q, f, 3 * N)) != SW_STATUS_OK) return fail("sw_eval", s);
  if ((s = sw_pdf(bsdf, &q, pdf, N)) != SW_STATUS_OK) return fail("sw_pdf", s);
  if ((s = sw_sample(bsdf, &q, u, swi, sweight, spdf)) != SW_STATUS_OK)
    return fail("sw_sample", s);
  /* The inputs, so the test evaluates exactly these. */
  for (int i = 0; i < 3 * N; i++) printf("wo %d %a\nwi %d %a\nu %d %a\n", i, wo[i], i, wi[i], i, u[i]);
  for (int i = 0; i < 2 * N; i++) printf("x %d %a\n", i, x[i]);
  for (int i = 0; i < 3 * N; i++) printf("eval %d %a\n", i, f[i]);
  for (int i = 0; i < N; i++) printf("pdf %d %a\n", i, pdf[i]);
  for (int i = 0; i < 3 * N; i++) printf("sample_wi %d %a\n", i, swi[i]);
  for (int i = 0; i < 3 * N; i++) printf("sample_weight %d %a\n", i, sweight[i]);
  for (int i = 0; i < N; i++) printf("sample_pdf %d %a\n", i, spdf[i]);

  /* One wavelength per query, spectral. */
  float lambda[N], f1[N];
  for (int i = 0; i < N; i++) lambda[i] = 380.0f + 6.0f * (float)i;
  SwQueries q1 = {N, wo, wi, x, NULL, lambda, 1, 1};
  if ((s = sw_eval(bsdf, &q1, f1, N)) != SW_STATUS_OK) return fail("sw_eval spectral", s);
  for (int i = 0; i < N; i++) printf("lambda %d %a\neval_spectral %d %a\n", i, lambda[i], i, f1[i]);

  /* Rejected inputs: a status and a message naming the field, nothing allocated. */
  SwBsdf *bad = NULL;
  s = sw_bsdf_from_json("{\"model\": \"velinov\", \"sigma_um\": -1}", NULL, NULL, &bad);
  printf("bad_status 0 %d\nbad_message 0 %s\nbad_handle 0 %d\n", (int)s, sw_last_error(),
         bad == NULL);
  s = sw_eval(bsdf, &q, f, 3 * N - 1);
  printf("short_status 0 %d\nshort_message 0 %s\n", (int)s, sw_last_error());

  sw_bsdf_free(bsdf);
  return 0;
}
