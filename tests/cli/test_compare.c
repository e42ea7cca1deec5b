/* `vkraycast compare` on files whose every difference is known: two 4x2 AOV files made
 * here (colour, hit, object, t, normal, shadow bits), two plain RGB files, and the verdicts,
 * metrics and exit statuses that idiff's conventions and docs/cli.md promise for them.
 * No Vulkan device is involved. Usage: test_compare VKRAYCAST */
#include <math.h>
#include <sys/stat.h>
#include <unistd.h>

#include "compare/aov.h"
#include "compare/heat_map.h"
#include "image/image_io.h"
#include "rc_test.h"
#include "rc_cli_test.h"

enum { W = 4, H = 2, C = RC_AOV_CHANNELS };
/* Channel order as rc_aov_channel_names: R G B hit object t N.X N.Y N.Z shadow uncertified
 * decisions (both left 0 here). */
static float A[W * H][C], B[W * H][C];

static const double NORMAL_ANGLE = 0.1; /* radians, pixel 4 */

static void make_pair(void) {
  for (int i = 0; i < W * H; i++) {
    const float p[C] = {0.25f, 0.5f, 0.75f, 1, 1, 100, 0, 0, 1, 0};
    memcpy(A[i], p, sizeof p);
    memcpy(B[i], p, sizeof p);
  }
  B[1][5] = 100.5f;                    /* pixel 1: depth 0.5 in 100, relative 0.005 */
  B[2][4] = 2, B[2][0] = 0.45f;        /* pixel 2: another object, red off by 0.2 */
  A[3][9] = 1, B[3][9] = 3, B[3][1] = 0.5001f; /* pixel 3: shadow bits 1 vs 3, green off by 1e-4 */
  B[4][6] = (float)sin(NORMAL_ANGLE), B[4][8] = (float)cos(NORMAL_ANGLE); /* pixel 4: normal tilted */
}

/* With meta: the header `vkraycast render` writes (scene hash, settings). */
static void write_exr_meta(const char *name, const float (*px)[C], int channels, const char *const *names,
                           const rc_image_meta *meta, int meta_count) {
  char path[300], err[256];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  float rows[W * H * C];
  for (int i = 0; i < W * H; i++)
    for (int k = 0; k < channels; k++) rows[i * channels + k] = px[i][k];
  rc_image_writer *w =
      rc_image_writer_open(path, W, H, channels, names, rc_encoding_linear(), false, meta, meta_count, err, sizeof err);
  CHECK(w != NULL);
  if (!w) return;
  CHECK_EQ_INT(rc_image_writer_rows(w, H, rows, err, sizeof err), 0);
  CHECK_EQ_INT(rc_image_writer_close(w, 1, err, sizeof err), 0);
}

static void write_exr(const char *name, const float (*px)[C], int channels, const char *const *names) {
  write_exr_meta(name, px, channels, names, NULL, 0);
}

static const cJSON *item(const cJSON *o, const char *key) { return cJSON_GetObjectItemCaseSensitive(o, key); }
static const char *json_string(const cJSON *o, const char *key) {
  const cJSON *v = item(o, key);
  return cJSON_IsString(v) ? v->valuestring : "";
}

static bool stdout_has(const char *text) {
  char path[300];
  snprintf(path, sizeof path, "%s/out.txt", tmp);
  FILE *f = fopen(path, "r");
  char buf[8192] = "";
  if (f) buf[fread(buf, 1, sizeof buf - 1, f)] = '\0', fclose(f);
  return strstr(buf, text) != NULL;
}

/* Colour metrics run over R, G and B only: t, ids and bitfields are not colours. */
TEST(aov_colour_metrics_leave_out_decision_channels) {
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --fail 1e-3 --decisions 9 --json > %s/m.json", tmp, tmp, tmp), 1);
  cJSON *j = load_json("m.json");
  CHECK(j != NULL);
  CHECK_EQ_INT(json_number(j, "colour_channels"), 3);
  CHECK_EQ_INT(json_number(j, "pixels_over"), 1); /* pixel 2 only: pixel 3's 1e-4 is under 1e-3 */
  CHECK_NEAR(json_number(j, "max_error"), 0.45f - 0.25f, 0);
  CHECK_EQ_INT(json_number(j, "max_x"), 2);
  CHECK_EQ_INT(json_number(j, "max_y"), 0);
  CHECK(strcmp(json_string(j, "max_channel_name"), "R") == 0);
  /* The worst pixel with every channel, by name. */
  CHECK_EQ_INT(json_number(item(j, "max_pixel_a"), "object"), 1);
  CHECK_EQ_INT(json_number(item(j, "max_pixel_b"), "object"), 2);
  CHECK_NEAR(json_number(item(j, "max_pixel_b"), "t"), 100, 0);
  /* PSNR over the 8 x 3 colour values, peak 1. */
  double d2 = (double)(0.45f - 0.25f) * (0.45f - 0.25f), g = (double)0.5001f - 0.5;
  double mse = (d2 + g * g) / (W * H * 3);
  CHECK_NEAR(json_number(j, "psnr"), 10 * log10(1 / mse), 1e-9);
  CHECK_NEAR(json_number(j, "mean_error"), ((0.45f - 0.25f) + g) / (W * H * 3), 1e-12);
  CHECK_EQ_INT(json_number(j, "object_mismatch"), 1);
  CHECK_EQ_INT(json_number(j, "shadow_mismatch"), 1);
  CHECK_EQ_INT(json_number(j, "hit_mismatch"), 0);
  CHECK_NEAR(json_number(j, "max_depth_rel_error"), 0.5 / 100.5, 1e-9); /* relative to B, the reference */
  CHECK_NEAR(json_number(j, "max_normal_angle"), NORMAL_ANGLE, 1e-6);
  CHECK(strcmp(json_string(j, "verdict"), "FAIL") == 0);
  cJSON_Delete(j);
}

/* idiff's verdicts with diff(1)'s exit statuses: PASS 0, WARNING 0, FAIL 1. */
TEST(verdicts_and_exit_status) {
  const char *ab = "compare %s/a.aov.exr %s/b.aov.exr --decisions 2 %s > %s/out.txt";
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3", tmp), 0); /* two pixels over the default --warn 1e-6 */
  CHECK(stdout_has("WARNING"));
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --warn 0.3", tmp), 0);
  CHECK(stdout_has("PASS"));
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --warnpercent 25", tmp), 0); /* 2 of 8 pixels: 25 % */
  CHECK(stdout_has("PASS"));
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --warnpercent 24", tmp), 0);
  CHECK(stdout_has("WARNING"));
  CHECK_EQ_INT(run(ab, tmp, tmp, "--failpercent 12.5 --fail 0.1 --warn 1", tmp), 0); /* 1 of 8 */
  CHECK_EQ_INT(run(ab, tmp, tmp, "--failpercent 12 --fail 0.1", tmp), 1);
  CHECK(stdout_has("FAIL"));
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --hardfail 0.19", tmp), 1);
  /* Decisions, depth and normals by their own limits. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --fail 0.3 --decisions 1 > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --depth-tolerance 0.0051", tmp), 0);
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --depth-tolerance 0.0049", tmp), 1);
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --normal-tolerance 0.11", tmp), 0);
  CHECK_EQ_INT(run(ab, tmp, tmp, "--fail 0.3 --normal-tolerance 0.09", tmp), 1);
  /* A file against itself is exact in every metric, the normal angle included. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/a.aov.exr --fail 0 --warn 0 --depth-tolerance 0 --normal-tolerance 0 "
                   "> %s/out.txt", tmp, tmp, tmp), 0);
  CHECK(stdout_has("PASS"));
}

/* The text report names the worst channel and prints both pixels whole. */
TEST(text_report_names_channels) {
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --decisions 9 --fail 1 --warn 1 > %s/out.txt", tmp, tmp, tmp), 0);
  CHECK(stdout_has("max error 0.2 in R at (2, 0)"));
  /* Channels in the file's order (OpenEXR may reorder them); every one is printed. */
  CHECK(stdout_has("A: R 0.25, G 0.5, B 0.75, "));
  CHECK(stdout_has("B: R 0.449999988, G 0.5, B 0.75, "));
  CHECK(stdout_has("object 1,") && stdout_has("object 2,") && stdout_has("t 100") && stdout_has("N.Z 1"));
  CHECK(stdout_has("decisions differ: hit 0, object 1, shadow 1 pixels"));
}

/* Plain images: every channel is a colour. */
TEST(plain_images_use_every_channel) {
  CHECK_EQ_INT(run("compare %s/a.exr %s/b.exr --fail 1e-3 --json > %s/p.json", tmp, tmp, tmp), 1);
  cJSON *j = load_json("p.json");
  CHECK_EQ_INT(json_number(j, "colour_channels"), 3);
  CHECK_EQ_INT(json_number(j, "pixels_over"), 1);
  CHECK(item(j, "object_mismatch") == NULL);
  cJSON_Delete(j);
}

/* The heat map is written before the verdict; when it cannot be, no verdict is printed
 * and the status is 2 (trouble), not PASS followed by a failure. */
TEST(heat_map_before_verdict) {
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --decisions 9 --fail 1 --diff %s/heat.png > %s/out.txt", tmp,
                   tmp, tmp, tmp), 0);
  struct stat st;
  char path[300];
  snprintf(path, sizeof path, "%s/heat.png", tmp);
  CHECK(stat(path, &st) == 0 && st.st_size > 0);
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --decisions 9 --fail 1 --diff %s/nodir/heat.png > %s/out.txt",
                   tmp, tmp, tmp, tmp), 2);
  CHECK(!stdout_has("PASS") && !stdout_has("FAIL"));
  CHECK(stderr_contains("no such directory"));
  CHECK_EQ_INT(run("compare %s/a.exr %s/b.exr --diff - > %s/out.txt", tmp, tmp, tmp), 2);
  CHECK(stderr_contains("not written to standard output"));
}

/* The check of one id in --json's list. */
static const cJSON *check_of(const cJSON *j, const char *id) {
  const cJSON *c;
  cJSON_ArrayForEach(c, item(j, "checks")) if (strcmp(json_string(c, "check"), id) == 0) return c;
  return NULL;
}

/* A preset applies the documented limits as shares of the image's pixels; options beside
 * it override them; the verdict line names each failing check with both numbers. */
TEST(presets_and_named_checks) {
  /* gpu-vs-cpu: 0.5 % of 8 pixels over 1e-3 is 0 pixels; pixel 2 is off by 0.2. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --preset gpu-vs-cpu --json > %s/p.json", tmp, tmp, tmp), 1);
  cJSON *j = load_json("p.json");
  CHECK(j != NULL);
  CHECK(strcmp(json_string(j, "preset"), "gpu-vs-cpu") == 0);
  CHECK_NEAR(json_number(j, "threshold"), 1e-3, 0);
  const cJSON *over = check_of(j, "pixels_over_fail"), *dec = check_of(j, "decisions");
  CHECK(over != NULL && dec != NULL);
  if (over && dec) {
    CHECK_EQ_INT(json_number(over, "measured"), 1);
    CHECK_EQ_INT(json_number(over, "allowed"), 0);
    CHECK(!cJSON_IsTrue(item(over, "ok")));
    CHECK(strcmp(json_string(over, "allowed_text"), "0.5 % = 0") == 0);
    CHECK_EQ_INT(json_number(dec, "measured"), 2); /* pixel 2's object, pixel 3's shadow */
    CHECK(strcmp(json_string(dec, "level"), "fail") == 0);
  }
  cJSON_Delete(j);
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --preset gpu-vs-cpu > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK(stdout_has("FAIL: pixels over --fail 0.001: 1 (12.5 %), allowed 0.5 % = 0; pixels whose first-sample "
                   "decisions differ: 2 (hit 0, object 1, shadow 1), allowed 0.2 % = 0\n"));
  CHECK(stdout_has("    FAIL pixels over --fail 0.001"));
  /* Overrides: 12.5 % allowed, 2 decisions allowed (a count replaces the preset's share). */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --preset gpu-vs-cpu --fail-percent 12.5 --decisions 2 "
                   "--warn 1 > %s/out.txt", tmp, tmp, tmp), 0);
  CHECK(stdout_has("PASS\n"));
  CHECK(stdout_has("allowed 12.5 % = 1\n"));
  /* --decisions-percent: 25 % of 8 pixels allows both. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --fail 1 --warn 1 --decisions-percent 25 > %s/out.txt", tmp,
                   tmp, tmp), 0);
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --fail 1 --warn 1 --decisions-percent 24 > %s/out.txt", tmp,
                   tmp, tmp), 1);
  CHECK(stdout_has("allowed 24 % = 1\n"));
  /* same-backend: bit-identical or FAIL; same-precision's PSNR floor is a check of its own,
   * over the pixels that decide alike: 6 here (pixels 2 and 3 decide otherwise), whose
   * colours are equal, so it passes; pixel 2's colour fails the share over --fail. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/a.aov.exr --preset same-backend > %s/out.txt", tmp, tmp, tmp), 0);
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --preset same-precision --json > %s/p.json", tmp, tmp, tmp), 1);
  j = load_json("p.json");
  const cJSON *psnr = check_of(j, "psnr");
  CHECK(psnr != NULL && cJSON_IsTrue(item(psnr, "ok")));
  if (psnr) CHECK_NEAR(json_number(psnr, "allowed"), 80, 0);
  CHECK_NEAR(json_number(j, "pixels_alike"), 6, 0);
  CHECK_NEAR(json_number(j, "psnr_alike"), 999, 0);
  CHECK(json_number(j, "psnr") < 30); /* pixel 2's 0.2 over all 8 pixels: 27.8 dB */
  cJSON_Delete(j);
  /* A warning names its check too. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --fail 1 --decisions 9 > %s/out.txt", tmp, tmp, tmp), 0);
  CHECK(stdout_has("WARNING: pixels over --warn 1e-06: 2 (25 %), allowed 0 % = 0\n"));
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --preset nearest > %s/out.txt", tmp, tmp, tmp), 2);
  CHECK(stderr_contains("expected one of same-backend, same-precision, gpu-vs-cpu, f32-vs-f64"));
}

/* An error past --fail where the first-sample decisions agree is explained: files without
 * the `decisions` channel (written before it) record the first sample's alone. */
TEST(first_sample_note) {
  static float c[W * H][C];
  memcpy(c, A, sizeof c);
  c[5][0] += 0.05f; /* pixel 5: colour only, decisions as in A */
  write_exr("c.aov.exr", (const float (*)[C])c, C - 1, rc_aov_channel_names);
  write_exr("a11.aov.exr", A, C - 1, rc_aov_channel_names);
  CHECK_EQ_INT(run("compare %s/c.aov.exr %s/a11.aov.exr --fail 1e-3 > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK(stdout_has("note: 1 of the 1 pixels over --fail 0.001 make the same first-sample decisions"));
  CHECK(stdout_has("Render both with --spp 1"));
  CHECK(stdout_has("or a texture lookup (not\n        recorded)"));
  /* Where the decisions differ there is no such note. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --fail 0.1 --decisions 9 > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK(!stdout_has("note: "));
}

/* With the digest of every sample's decisions (packed_aov.decisions) in both files, a pixel
 * whose first sample agrees but whose digests differ made another decision in a later
 * sample or bounce: a decision mismatch, and for a certified pixel a broken certificate;
 * where the digests agree too, the note says the difference is colour alone. */
TEST(every_sample_digest) {
  static float c[W * H][C], d[W * H][C];
  memcpy(c, A, sizeof c);
  memcpy(d, A, sizeof d);
  for (int i = 0; i < W * H; i++) c[i][11] = d[i][11] = (float)(1000 + i);
  c[5][0] += 0.05f;  /* pixel 5: colour only, every sample's decisions the same */
  d[6][11] = 77;     /* pixel 6: a later sample decided otherwise, the first did not */
  d[6][1] += 0.05f;
  write_exr("c.aov.exr", (const float (*)[C])c, C, rc_aov_channel_names);
  write_exr("d.aov.exr", (const float (*)[C])d, C, rc_aov_channel_names);
  CHECK_EQ_INT(run("compare %s/c.aov.exr %s/d.aov.exr --fail 1e-3 --json > %s/m.json", tmp, tmp, tmp), 1);
  cJSON *j = load_json("m.json");
  CHECK_NEAR(json_number(j, "sample_mismatch"), 1, 0);
  CHECK_NEAR(json_number(j, "hit_mismatch") + json_number(j, "object_mismatch") + json_number(j, "shadow_mismatch"), 0,
             0);
  CHECK_NEAR(json_number(j, "over_same_decisions"), 1, 0); /* pixel 5 */
  /* A's pixels are certified (uncertified 0): pixel 6's other decision breaks its certificate. */
  CHECK_NEAR(json_number(j, "certified_mismatch"), 1, 0);
  cJSON_Delete(j);
  CHECK_EQ_INT(run("compare %s/c.aov.exr %s/d.aov.exr --fail 1e-3 > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK(stdout_has("decisions of every sample and bounce differ: 1 pixels\n"));
  CHECK(stdout_has("note: 1 of the 2 pixels over --fail 0.001 make the same decisions in A and B, in every\n"));
  /* same-precision's PSNR runs over the 7 pixels that decide alike in every sample: pixel
   * 5's 0.05 in one channel of 21 gives 39.2 dB and fails; without it, pixel 6's flip
   * alone is left to the shares over --fail (0.01 % of 8 pixels: 0), and the PSNR passes. */
  CHECK_EQ_INT(run("compare %s/c.aov.exr %s/d.aov.exr --preset same-precision --json > %s/m.json", tmp, tmp, tmp), 1);
  j = load_json("m.json");
  const cJSON *psnr = check_of(j, "psnr");
  CHECK(psnr != NULL && !cJSON_IsTrue(item(psnr, "ok")));
  CHECK_NEAR(json_number(j, "pixels_alike"), 7, 0);
  CHECK_NEAR(json_number(j, "psnr_alike"), 10 * log10(21 / (0.05 * 0.05)), 0.01);
  cJSON_Delete(j);
  c[5][0] = A[5][0];
  write_exr("c.aov.exr", (const float (*)[C])c, C, rc_aov_channel_names);
  CHECK_EQ_INT(run("compare %s/c.aov.exr %s/d.aov.exr --preset same-precision --json > %s/m.json", tmp, tmp, tmp), 1);
  j = load_json("m.json");
  psnr = check_of(j, "psnr");
  CHECK(psnr != NULL && cJSON_IsTrue(item(psnr, "ok")));
  CHECK_NEAR(json_number(j, "psnr_alike"), 999, 0);
  const cJSON *over = check_of(j, "pixels_over_fail");
  CHECK(over != NULL && !cJSON_IsTrue(item(over, "ok")));
  cJSON_Delete(j);
  CHECK_EQ_INT(run("compare %s/c.aov.exr %s/d.aov.exr --fail 1e-3 > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK(stdout_has("  the 7 pixels that decide alike: the same colour\n"));
  c[5][0] += 0.05f;
  /* Files without the channel compare by the first sample, as before, and so does PSNR. */
  write_exr("c11.aov.exr", (const float (*)[C])c, C - 1, rc_aov_channel_names);
  write_exr("d11.aov.exr", (const float (*)[C])d, C - 1, rc_aov_channel_names);
  CHECK_EQ_INT(run("compare %s/c11.aov.exr %s/d11.aov.exr --fail 1e-3 --json > %s/m.json", tmp, tmp, tmp), 1);
  j = load_json("m.json");
  CHECK(item(j, "sample_mismatch") == NULL);
  CHECK(item(j, "psnr_alike") == NULL);
  CHECK_NEAR(json_number(j, "certified_mismatch"), 0, 0);
  cJSON_Delete(j);
}

/* +Inf equals +Inf; NaN equals NaN; NaN against a number is reported as such and makes
 * PSNR undefined (never 999 or infinite). */
TEST(non_finite_values) {
  static float x[W * H][C], y[W * H][C];
  memcpy(x, A, sizeof x);
  memcpy(y, A, sizeof y);
  x[0][0] = y[0][0] = INFINITY;
  x[1][1] = y[1][1] = NAN;
  write_exr("inf_a.exr", (const float (*)[C])x, 3, NULL);
  write_exr("inf_b.exr", (const float (*)[C])y, 3, NULL);
  CHECK_EQ_INT(run("compare %s/inf_a.exr %s/inf_b.exr --fail 0 --warn 0 --json > %s/n.json", tmp, tmp, tmp), 0);
  cJSON *j = load_json("n.json");
  CHECK_EQ_INT(json_number(j, "max_error"), 0);
  CHECK_EQ_INT(json_number(j, "nonfinite_mismatch"), 0);
  CHECK_EQ_INT(json_number(j, "psnr"), 999); /* identical: JSON's spelling of infinity */
  cJSON_Delete(j);
  y[2][2] = NAN;  /* against 0.75 */
  y[3][0] = -INFINITY; /* against 0.25 */
  write_exr("inf_b.exr", (const float (*)[C])y, 3, NULL);
  CHECK_EQ_INT(run("compare %s/inf_a.exr %s/inf_b.exr --fail 1 --json > %s/n.json", tmp, tmp, tmp), 1);
  j = load_json("n.json");
  CHECK_EQ_INT(json_number(j, "nonfinite_mismatch"), 2);
  CHECK(cJSON_IsNull(item(j, "psnr")));
  const cJSON *nf = check_of(j, "nonfinite");
  CHECK(nf != NULL && !cJSON_IsTrue(item(nf, "ok")));
  cJSON_Delete(j);
  CHECK_EQ_INT(run("compare %s/inf_a.exr %s/inf_b.exr --fail 1 > %s/out.txt", tmp, tmp, tmp), 1);
  CHECK(stdout_has("PSNR undefined"));
  CHECK(stdout_has("note: PSNR is undefined: 2 colour values are NaN or infinite in one file"));
  CHECK(!stdout_has("999") && !stdout_has("inf dB"));
}

/* The headers `render` writes: the same scene or not, every setting that differs. */
TEST(header_aware) {
  const rc_image_meta gpu[] = {{"vkraycast:scene_hash", "00000000000000aa"},
                               {"vkraycast:settings", "backend=gpu precision=f32 spp=4 shadows=on"}};
  const rc_image_meta cpu[] = {{"vkraycast:scene_hash", "00000000000000aa"},
                               {"vkraycast:settings", "backend=cpu precision=f64 spp=4 shadows=on"}};
  const rc_image_meta other[] = {{"vkraycast:scene_hash", "00000000000000bb"},
                                 {"vkraycast:settings", "backend=gpu precision=f32 spp=4"}};
  write_exr_meta("h_gpu.exr", (const float (*)[C])A, 3, NULL, gpu, 2);
  write_exr_meta("h_cpu.exr", (const float (*)[C])A, 3, NULL, cpu, 2);
  write_exr_meta("h_other.exr", (const float (*)[C])A, 3, NULL, other, 2);
  CHECK_EQ_INT(run("compare %s/h_gpu.exr %s/h_cpu.exr --require-same-scene > %s/out.txt", tmp, tmp, tmp), 0);
  CHECK(stdout_has("headers: the same scene (00000000000000aa); settings differ (A / B): backend gpu / cpu, "
                   "precision f32 / f64\n"));
  CHECK_EQ_INT(run("compare %s/h_gpu.exr %s/h_other.exr > %s/out.txt", tmp, tmp, tmp), 0);
  CHECK(stdout_has("DIFFERENT SCENES (A 00000000000000aa, B 00000000000000bb)"));
  CHECK(stdout_has("shadows on / (none)"));
  CHECK_EQ_INT(run("compare %s/h_gpu.exr %s/h_other.exr --json > %s/h.json", tmp, tmp, tmp), 0);
  cJSON *j = load_json("h.json");
  const cJSON *h = item(j, "headers");
  CHECK(cJSON_IsFalse(item(h, "same_scene")));
  CHECK_EQ_INT(cJSON_GetArraySize(item(h, "settings_differ")), 1);
  cJSON_Delete(j);
  CHECK_EQ_INT(run("compare %s/h_gpu.exr %s/h_other.exr --require-same-scene > %s/out.txt", tmp, tmp, tmp), 2);
  CHECK(stderr_contains("different scenes (--require-same-scene)"));
  CHECK(!stdout_has("PASS"));
  CHECK_EQ_INT(run("compare %s/h_gpu.exr %s/a.exr --require-same-scene > %s/out.txt", tmp, tmp, tmp), 2);
  CHECK(stderr_contains("a.exr: no vkraycast header"));
}

static float *read_png(const char *name, int *w, int *h) {
  char path[300], err[256];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  int c = 0;
  float *px = NULL;
  if (rc_image_read(path, w, h, &c, &px, err, sizeof err) != 0 || c != 3) {
    printf("  cannot read %s: %s\n", path, err);
    free(px);
    return NULL;
  }
  return px;
}

/* The heat map: the fixed scale's colour per pixel over the reference in grey, the
 * worst pixel enlarged, and a legend that depends on the scale alone. */
TEST(heat_map_readable) {
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --decisions 9 --fail 1e-3 --diff %s/h1.png > %s/out.txt", tmp,
                   tmp, tmp, tmp), 1);
  CHECK(stdout_has("log scale 1e-06 .. 1 over B in grey"));
  CHECK(stdout_has("1 pixel over it ringed"));
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/a.aov.exr --fail 1e-3 --diff %s/h2.png > %s/out.txt", tmp, tmp, tmp, tmp),
               0);
  int w = 0, h = 0, w2 = 0, h2 = 0;
  float *p1 = read_png("h1.png", &w, &h), *p2 = read_png("h2.png", &w2, &h2);
  CHECK(p1 && p2);
  if (!p1 || !p2) goto done;
  CHECK_EQ_INT(w, RC_HEAT_MIN_WIDTH);
  CHECK_EQ_INT(h, H + RC_HEAT_LEGEND);
  /* Pixel 2 (x 2, y 0) is off by 0.2: its colour on the scale 1e-6 .. 1, opaque. */
  float want[3];
  rc_heat_colour((log10(0.45 - 0.25) + 6) / 6, want);
  for (int k = 0; k < 3; k++) CHECK_NEAR(p1[3 * 2 + k], want[k], 1.0 / 255);
  /* Enlarged: its neighbour below (not over the threshold itself) takes its colour. */
  for (int k = 0; k < 3; k++) CHECK_NEAR(p1[3 * (w + 2) + k], want[k], 1.0 / 255);
  /* Identical pixels show the reference in grey (B's 0.25, 0.5, 0.75 averages to 0.5). */
  float grey = (float)(0.08 + 0.30 * sqrt(0.5));
  for (int k = 0; k < 3; k++) CHECK_NEAR(p2[3 * 1 + k], grey, 1.0 / 255);
  /* The legend depends on the scale and the --fail mark alone: identical in both maps. */
  CHECK(memcmp(p1 + 3 * (size_t)w * H, p2 + 3 * (size_t)w * H, sizeof(float) * 3 * (size_t)w * RC_HEAT_LEGEND) == 0);
  /* The bar starts at the scale's first colour. */
  float first[3];
  rc_heat_colour(0, first);
  for (int k = 0; k < 3; k++) CHECK_NEAR(p1[3 * ((size_t)(H + 15) * w + 10) + k], first[k], 1.0 / 255);
  /* Another scale moves pixel 2 on it. */
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --decisions 9 --fail 1 --scale 1e-3,1e-1 --diff %s/h3.png "
                   "> %s/out.txt", tmp, tmp, tmp, tmp), 0);
  free(p2);
  p2 = read_png("h3.png", &w2, &h2);
  rc_heat_colour(1, want); /* 0.2 is past the top, 1e-1 */
  for (int k = 0; p2 && k < 3; k++) CHECK_NEAR(p2[3 * 2 + k], want[k], 1.0 / 255);
  CHECK_EQ_INT(run("compare %s/a.aov.exr %s/b.aov.exr --scale 1,0.5 --diff %s/h4.png > %s/out.txt", tmp, tmp, tmp,
                   tmp), 2);
  CHECK(stderr_contains("--scale: expected LO,HI with 0 < LO < HI"));
done:
  free(p1);
  free(p2);
}

/* What an 8-bit file stores under each encoding (image_io.h): one pixel through a PNG and
 * back, as levels of 255. Values chosen to land on a level, away from rounding's edge:
 * gamma 2 takes 0.16 to 0.4 (102); exposure +1 takes 0.2 to 0.4, -2 takes 0.8 to 0.2
 * (51); sRGB takes 0.2 to 0.4845 (123.55, so 124) with exposure 0 as before exposure
 * existed; a float file keeps the linear value whatever the encoding. */
static int level_after(rc_encoding e, float linear, const char *ext) {
  char path[300], err[256];
  snprintf(path, sizeof path, "%s/level%s", tmp, ext);
  const float px[3] = {linear, linear, linear};
  if (rc_image_write(path, 1, 1, 3, px, e, false, err, sizeof err) != 0) return -1;
  int w, h, c;
  float *back = NULL;
  if (rc_image_read(path, &w, &h, &c, &back, err, sizeof err) != 0) return -1;
  float v = back[0];
  free(back);
  return strcmp(ext, ".png") == 0 ? (int)lroundf(v * 255.0f) : (v == linear ? 1 : 0);
}

TEST(eight_bit_encodings) {
  rc_encoding gamma2 = {RC_CURVE_GAMMA, 2.0f, 0.0f}, up = {RC_CURVE_LINEAR, 1.0f, 1.0f},
              down = {RC_CURVE_LINEAR, 1.0f, -2.0f}, srgb = {RC_CURVE_SRGB, 1.0f, 0.0f},
              gamma22 = {RC_CURVE_GAMMA, 2.2f, 0.0f}, all = {RC_CURVE_GAMMA, 2.2f, 3.0f};
  CHECK_EQ_INT(level_after(gamma2, 0.16f, ".png"), 102);
  CHECK_EQ_INT(level_after(rc_encoding_linear(), 0.16f, ".png"), 41);
  CHECK_EQ_INT(level_after(up, 0.2f, ".png"), 102);
  CHECK_EQ_INT(level_after(down, 0.8f, ".png"), 51);
  CHECK_EQ_INT(level_after(up, 0.9f, ".png"), 255); /* past white: clamped after the scale */
  CHECK_EQ_INT(level_after(srgb, 0.2f, ".png"), 124);
  CHECK_EQ_INT(level_after(gamma22, 1.0f, ".png"), 255);
  CHECK_EQ_INT(level_after(gamma22, 0.0f, ".png"), 0);
  CHECK_EQ_INT(level_after(gamma22, -0.5f, ".png"), 0);
  CHECK_EQ_INT(level_after(all, 0.3f, ".exr"), 1);
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: test_compare VKRAYCAST\n");
    return 2;
  }
  bin = argv[1];
  snprintf(tmp, sizeof tmp, "/tmp/vkraycast_compare_XXXXXX");
  if (!mkdtemp(tmp)) return 2;
  make_pair();
  write_exr("a.aov.exr", (const float (*)[C])A, C, rc_aov_channel_names);
  write_exr("b.aov.exr", (const float (*)[C])B, C, rc_aov_channel_names);
  write_exr("a.exr", (const float (*)[C])A, 3, NULL);
  write_exr("b.exr", (const float (*)[C])B, 3, NULL);
  TEST_MAIN_BEGIN
  RUN(aov_colour_metrics_leave_out_decision_channels);
  RUN(verdicts_and_exit_status);
  RUN(text_report_names_channels);
  RUN(plain_images_use_every_channel);
  RUN(heat_map_before_verdict);
  RUN(presets_and_named_checks);
  RUN(first_sample_note);
  RUN(every_sample_digest);
  RUN(non_finite_values);
  RUN(header_aware);
  RUN(heat_map_readable);
  RUN(eight_bit_encodings);
  char cleanup[300];
  snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", tmp);
  if (!getenv("KEEP") && system(cleanup) != 0) printf("could not remove %s\n", tmp);
  TEST_MAIN_END
}
