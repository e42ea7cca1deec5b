/* `vkraycast compare` on files whose every difference is known: two 4x2 AOV files made
 * here (colour, hit, object, t, normal, shadow bits), two plain RGB files, and the verdicts,
 * metrics and exit statuses that idiff's conventions and docs/cli.md promise for them.
 * No Vulkan device is involved. Usage: test_compare VKRAYCAST */
#include <math.h>
#include <sys/stat.h>
#include <unistd.h>

#include "compare/aov.h"
#include "image/image_io.h"
#include "rc_test.h"
#include "rc_cli_test.h"

enum { W = 4, H = 2, C = RC_AOV_CHANNELS };
/* Channel order as rc_aov_channel_names: R G B hit object t N.X N.Y N.Z shadow. */
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

static void write_exr(const char *name, const float (*px)[C], int channels, const char *const *names) {
  char path[300], err[256];
  snprintf(path, sizeof path, "%s/%s", tmp, name);
  float rows[W * H * C];
  for (int i = 0; i < W * H; i++)
    for (int k = 0; k < channels; k++) rows[i * channels + k] = px[i][k];
  rc_image_writer *w = rc_image_writer_open(path, W, H, channels, names, RC_ENCODING_LINEAR, false, NULL, 0, err, sizeof err);
  CHECK(w != NULL);
  if (!w) return;
  CHECK_EQ_INT(rc_image_writer_rows(w, H, rows, err, sizeof err), 0);
  CHECK_EQ_INT(rc_image_writer_close(w, 1, err, sizeof err), 0);
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
  char cleanup[300];
  snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", tmp);
  if (!getenv("KEEP") && system(cleanup) != 0) printf("could not remove %s\n", tmp);
  TEST_MAIN_END
}
