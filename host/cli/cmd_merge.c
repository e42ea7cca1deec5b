/* cmd_merge.c: `vkraycast merge PARTS... -o OUT`: the parts of one frame (render --shard,
 * --region) into the image a single render would have written, bit for bit; or the parts'
 * AOV files (render --aov) into the single render's AOV file. Every part is checked
 * before anything is written: an EXR of 32-bit float RGB (or of the AOV channels) whose header
 * (part.h) agrees with the first part's on the frame, the scene and every setting that
 * changes a pixel, and whose regions cover the frame exactly once. The image is then
 * streamed in bands of rows through the same writer as `render` (output.h): no part is
 * ever whole in memory, and a failure leaves no file behind (docs/cluster.md). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/options.h"
#include "cli/output.h"
#include "cli/part.h"
#include "compare/aov.h"
#include "scene/scene.h"

#define MAX_PARTS 4096u
/* Rows per band of the merged image. */
#define BAND_ROWS 64u

typedef struct {
  const char *parts[MAX_PARTS];
  const char *output;
  bool quiet;
} merge_args;

#define ARG(field) offsetof(merge_args, field)
static const rc_option merge_options[] = {
    {"--output", "-o", RC_OPT_STRING, ARG(output), "OUT", .flags = RC_OPT_REQUIRED, .what = "output file",
     .help = "the merged image; any format `render` writes (png, exr, tif, jpg, ...),\n"
             "with the parts' encoding and quantization"},
    {"--quiet", "-q", RC_OPT_FLAG, ARG(quiet), .help = "no summary on stderr"},
};
#undef ARG

static const char *const merge_positional[] = {"part"};
const rc_command_spec rc_merge_spec = {
    .name = "merge",
    .synopsis = "PART.exr... -o OUT [options]",
    .summary = "Joins the parts of one frame (render --shard I/N or --region, written as .exr) into the image a\n"
               "single render writes, bit for bit; their AOV files (render --aov) into its AOV file. Refuses\n"
               "parts that leave a pixel uncovered or cover one twice, or that disagree on the scene or a\n"
               "setting, naming the part or the missing region.",
    .epilogue = "Exit status: 0 written; 2 bad input or usage (nothing written); 3 memory failure.\n",
    .min_positional = 1,
    .max_positional = MAX_PARTS,
    .positional_offset = offsetof(merge_args, parts),
    .positional_names = merge_positional,
    .options = merge_options,
    .option_count = sizeof merge_options / sizeof *merge_options,
};

typedef struct {
  const char *path;
  rc_part_info info;
  rc_image_reader *reader; /* open while the band being written meets the part */
  float *rows;             /* one band's worth of the part's rows */
  int channels;            /* 3 (an image) or RC_AOV_CHANNELS (an AOV file) */
  int from[RC_AOV_CHANNELS]; /* the file's channel holding each channel of the output */
} part;

/* What a part is, from its channels: an image (3 float channels) or an AOV file (every AOV
 * channel, in whatever order the file stores them: OpenEXR sorts them by name); fills
 * p->channels and p->from. False when neither. */
static bool part_layout(part *p, int c) {
  p->channels = c;
  if (c == 3) {
    for (int i = 0; i < 3; i++) p->from[i] = i;
    return true;
  }
  if (c != RC_AOV_CHANNELS) return false;
  for (int i = 0; i < RC_AOV_CHANNELS; i++) {
    p->from[i] = -1;
    for (int j = 0; j < c; j++) {
      char name[32];
      if (rc_image_reader_channel(p->reader, j, name, sizeof name) && strcmp(name, rc_aov_channel_names[i]) == 0)
        p->from[i] = j;
    }
    if (p->from[i] < 0) return false;
  }
  return true;
}

/* Opens a part and reads its header; the reader stays open. */
static rc_status open_part(part *p) {
  char err[512];
  int w, hgt, c;
  bool f32;
  /* Opened without blocking and refused unless a regular file, as render's inputs are: a
   * FIFO part would hang the image library's open. */
  if (rc_check_input(p->path, "part", NULL) != RC_OK) return RC_ERR_IO;
  p->reader = rc_image_reader_open(p->path, &w, &hgt, &c, &f32, err, sizeof err);
  if (!p->reader) {
    rc_error("%s: cannot read the part: %s", p->path, err);
    return RC_ERR_IO;
  }
  const char *missing;
  if (!rc_part_read(p->reader, &p->info, &missing)) {
    rc_error("%s: not a part of a vkraycast render: its header has no valid \"%s\" (render it with `vkraycast "
             "render --shard I/N` or `--region` to a .exr file)",
             p->path, missing);
    return RC_ERR_INPUT;
  }
  /* What the header declares, against what a render writes: a frame no render makes, or a
   * region or shard outside its own frame, is refused before anything is sized by it. */
  const rc_part_info *h = &p->info;
  const rc_region g = h->region;
  if (h->width == 0 || h->height == 0 || h->width > RC_MAX_IMAGE_SIDE || h->height > RC_MAX_IMAGE_SIDE) {
    rc_error("%s: its header's frame %u x %u is not one a render writes (1 to %u pixels a side)", p->path, h->width,
             h->height, RC_MAX_IMAGE_SIDE);
    return RC_ERR_INPUT;
  }
  if (g.x0 >= g.x1 || g.y0 >= g.y1 || g.x1 > h->width || g.y1 > h->height) {
    rc_error("%s: its header's region %u,%u,%u,%u (X0,Y0,X1,Y1) is empty or leaves its %u x %u frame", p->path, g.x0,
             g.y0, g.x1, g.y1, h->width, h->height);
    return RC_ERR_INPUT;
  }
  if (h->shard_count && (h->shard_index >= h->shard_count || h->shard_count > h->height)) {
    rc_error("%s: its header's shard %u/%u is not one of a %u-row frame (0 <= I < N <= rows)", p->path,
             h->shard_index, h->shard_count, h->height);
    return RC_ERR_INPUT;
  }
  /* A lossy recompression changed the render's pixels: the merge could not be its image. */
  char compression[64];
  if (rc_image_reader_meta(p->reader, "compression", compression, sizeof compression)) {
    static const char *const lossy[] = {"dwaa", "dwab", "b44", "pxr24"};
    for (size_t i = 0; i < sizeof lossy / sizeof *lossy; i++) {
      if (strncmp(compression, lossy[i], strlen(lossy[i])) == 0) {
        rc_error("%s: the part is compressed lossily (%s): its pixels are no longer the render's; merge the "
                 "part render wrote",
                 p->path, compression);
        return RC_ERR_INPUT;
      }
    }
  }
  if (!f32 || !part_layout(p, c)) {
    rc_error("%s: the part holds %d channel(s)%s; a part is 3 channels of 32-bit float (write it as .exr), or the %d "
             "channels of an AOV file (render --aov)",
             p->path, c, f32 ? "" : " not all 32-bit float", RC_AOV_CHANNELS);
    return RC_ERR_INPUT;
  }
  if ((uint32_t)w != rc_region_width(g) || (uint32_t)hgt != rc_region_height(g)) {
    rc_error("%s: the part is %d x %d pixels, but its header's region %u,%u,%u,%u is %u x %u", p->path, w, hgt, g.x0,
             g.y0, g.x1, g.y1, rc_region_width(g), rc_region_height(g));
    return RC_ERR_INPUT;
  }
  return RC_OK;
}

/* Every part against the first: the frame, the scene, the settings. */
static rc_status check_agreement(const part *parts, size_t n) {
  const rc_part_info *a = &parts[0].info;
  bool warned = false;
  for (size_t i = 1; i < n; i++) {
    const rc_part_info *b = &parts[i].info;
    char x[128], y[128];
    if (parts[i].channels != parts[0].channels) {
      rc_error("%s is %s, but %s is %s: merge the images and the AOV files separately", parts[i].path,
               parts[i].channels == 3 ? "an image" : "an AOV file", parts[0].path,
               parts[0].channels == 3 ? "an image" : "an AOV file");
      return RC_ERR_INPUT;
    }
    if (b->width != a->width || b->height != a->height) {
      rc_error("%s: a part of a %u x %u frame, but %s is of a %u x %u frame: parts of different renders",
               parts[i].path, b->width, b->height, parts[0].path, a->width, a->height);
      return RC_ERR_INPUT;
    }
    if (rc_part_settings_differ(a->settings, b->settings, x, sizeof x, y, sizeof y)) {
      rc_error("%s: rendered with %s, but %s with %s: a merged image would not be any single render's",
               parts[i].path, y, parts[0].path, x);
      return RC_ERR_INPUT;
    }
    if (strcmp(a->scene_hash, b->scene_hash) != 0) {
      rc_error("%s: its packed scene (hash %s) is not that of %s (hash %s): the scene file changed between the "
               "renders, or they are of different scenes",
               parts[i].path, b->scene_hash, parts[0].path, a->scene_hash);
      return RC_ERR_INPUT;
    }
    if (!warned && strcmp(a->device, b->device) != 0) {
      rc_warning("%s was rendered on %s, %s on %s: GPUs of different makes may round differently, so the merged "
                 "image can differ from a single render in the last bits",
                 parts[0].path, a->device, parts[i].path, b->device);
      warned = true;
    }
  }
  return RC_OK;
}

static int shard_order(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return x < y ? -1 : x > y;
}

/* The shards of `count` that no part holds, the first few by number and then how many
 * more: sorted, so O(n log n) whatever count the headers declare. */
static void note_missing_shards(const part *parts, size_t n, uint32_t count) {
  uint32_t *have = rc_alloc(n, sizeof *have, "the parts' shard numbers");
  if (!have) return;
  for (size_t i = 0; i < n; i++) have[i] = parts[i].info.shard_index;
  qsort(have, n, sizeof *have, shard_order);
  enum { SHOWN = 8 };
  uint64_t missing = 0;
  uint32_t shown = 0, k = 0; /* shards below k are accounted for */
  for (size_t i = 0; i <= n; i++) {
    uint32_t next = i < n ? have[i] : count; /* shards [k, next) are missing */
    if (next > k) {
      for (uint32_t m = k; m < next && shown < SHOWN; m++, shown++)
        fprintf(stderr, "vkraycast: note: shard %u/%u is missing: render it again with `--shard %u/%u` (under "
                        "Slurm: sbatch --array=%u ...; docs/cluster.md)\n",
                m, count, m, count, m);
      missing += next - k;
    }
    if (i < n && have[i] >= k) k = have[i] + 1;
  }
  if (missing > shown)
    fprintf(stderr, "vkraycast: note: and %llu more of the %u shards are missing\n",
            (unsigned long long)(missing - shown), count);
  free(have);
}

/* The regions cover the frame exactly once; else the parts that overlap, or the first
 * uncovered region and, for shards, the missing ones. */
static rc_status check_coverage(const part *parts, size_t n) {
  rc_region *regions = rc_alloc(n, sizeof *regions, "the parts' regions");
  if (!regions) return RC_ERR_OUT_OF_MEMORY;
  for (size_t i = 0; i < n; i++) regions[i] = parts[i].info.region;
  const uint32_t w = parts[0].info.width, h = parts[0].info.height;
  size_t a = 0, b = 0;
  rc_region gap = {0};
  int verdict = rc_region_coverage(regions, n, w, h, &a, &b, &gap);
  free(regions);
  if (verdict == 0) return RC_OK;
  if (verdict == 4) {
    rc_error("out of memory checking the coverage of %zu parts", n);
    return RC_ERR_OUT_OF_MEMORY;
  }
  if (verdict == 3) {
    const rc_region r = parts[a].info.region;
    rc_error("%s: its region %u,%u,%u,%u leaves the %u x %u frame", parts[a].path, r.x0, r.y0, r.x1, r.y1, w, h);
  } else if (verdict == 1) {
    const rc_region p = parts[a].info.region, q = parts[b].info.region;
    rc_error("%s and %s both hold the pixels %u,%u,%u,%u (X0,Y0,X1,Y1): each pixel must come from one part%s",
             parts[a].path, parts[b].path, p.x0 > q.x0 ? p.x0 : q.x0, p.y0 > q.y0 ? p.y0 : q.y0,
             p.x1 < q.x1 ? p.x1 : q.x1, p.y1 < q.y1 ? p.y1 : q.y1,
             parts[a].info.shard_count && parts[b].info.shard_count ? " (the same shard given twice, or shards of "
                                                                        "different counts)"
                                                                      : "");
  } else {
    rc_error("no part holds the pixels %u,%u,%u,%u (X0,Y0,X1,Y1) of the %u x %u frame", gap.x0, gap.y0, gap.x1, gap.y1,
             w, h);
    /* Shards of one count: name the missing ones, the way to render them again. */
    uint32_t count = parts[0].info.shard_count;
    bool shards = count > 0;
    for (size_t i = 0; i < n; i++) shards = shards && parts[i].info.shard_count == count;
    if (shards) note_missing_shards(parts, n, count);
  }
  return RC_ERR_INPUT;
}

static void close_parts(part *parts, size_t n) {
  for (size_t i = 0; i < n; i++) {
    rc_image_reader_close(parts[i].reader);
    parts[i].reader = NULL;
    free(parts[i].rows);
    parts[i].rows = NULL;
  }
}

static const part *sort_parts; /* qsort's context: the parts ordered by their first row */
static int first_row_order(const void *a, const void *b) {
  const rc_region *x = &sort_parts[*(const size_t *)a].info.region, *y = &sort_parts[*(const size_t *)b].info.region;
  if (x->y0 != y->y0) return x->y0 < y->y0 ? -1 : 1;
  return x->x0 < y->x0 ? -1 : x->x0 > y->x0;
}

/* Band after band of the frame, each assembled from the parts that meet it; a part is
 * open from the first band that meets it to its last. The parts are visited in the order
 * of their first rows, so that each band looks at the parts that meet it only. */
static rc_status write_merged(part *parts, size_t n, rc_output *out) {
  const uint32_t w = parts[0].info.width, h = parts[0].info.height;
  const int nc = parts[0].channels;
  float *band = rc_alloc((size_t)w * BAND_ROWS * (size_t)nc, sizeof(float), "one band of the image");
  size_t *order = rc_alloc(n, sizeof *order, "the parts' order"), *active = rc_alloc(n, sizeof *active, "the parts' order");
  if (!band || !order || !active) {
    free(band);
    free(order);
    free(active);
    return RC_ERR_OUT_OF_MEMORY;
  }
  for (size_t i = 0; i < n; i++) order[i] = i;
  sort_parts = parts;
  qsort(order, n, sizeof *order, first_row_order);
  size_t started = 0, live = 0; /* order[0, started) met a band; active[0, live) still do */
  rc_status st = RC_OK;
  char err[512];
  for (uint32_t y0 = 0; st == RC_OK && y0 < h; y0 += BAND_ROWS) {
    uint32_t y1 = y0 + BAND_ROWS < h ? y0 + BAND_ROWS : h;
    while (started < n && parts[order[started]].info.region.y0 < y1) active[live++] = order[started++];
    for (size_t j = 0; st == RC_OK && j < live;) {
      part *p = &parts[active[j]];
      const rc_region r = p->info.region;
      uint32_t a = r.y0 > y0 ? r.y0 : y0, b = r.y1 < y1 ? r.y1 : y1, pw = rc_region_width(r);
      if (!p->reader) { /* the first band that meets the part */
        int pw_, ph_, c_;
        bool f32_;
        p->reader = rc_image_reader_open(p->path, &pw_, &ph_, &c_, &f32_, err, sizeof err);
        if (!p->reader) {
          rc_error("%s: cannot read the part: %s", p->path, err);
          st = RC_ERR_IO;
          break;
        }
      }
      if (!p->rows) p->rows = rc_alloc((size_t)pw * BAND_ROWS * (size_t)nc, sizeof(float), "one band of a part");
      if (!p->rows) {
        st = RC_ERR_OUT_OF_MEMORY;
        break;
      }
      if (rc_image_reader_rows(p->reader, (int)(a - r.y0), (int)(b - r.y0), p->rows, err, sizeof err) != 0) {
        rc_error("%s: cannot read rows %u to %u of the part: %s", p->path, a - r.y0, b - r.y0, err);
        st = RC_ERR_IO;
        break;
      }
      for (uint32_t y = a; y < b; y++) {
        float *dst = band + (size_t)nc * ((size_t)(y - y0) * w + r.x0);
        const float *src = p->rows + (size_t)nc * (size_t)(y - a) * pw;
        for (uint32_t x = 0; x < pw; x++)
          for (int c = 0; c < nc; c++) dst[(size_t)nc * x + c] = src[(size_t)nc * x + p->from[c]];
      }
      if (r.y1 <= y1) { /* the part's last rows: done with it */
        rc_image_reader_close(p->reader);
        p->reader = NULL;
        free(p->rows);
        p->rows = NULL;
        active[j] = active[--live];
      } else {
        j++;
      }
    }
    if (st == RC_OK)
      st = nc == 3 ? rc_output_band(y0, y1 - y0, band, NULL, NULL, out) : rc_output_aov_rows(out, y1 - y0, band);
  }
  free(band);
  free(order);
  free(active);
  return st;
}

rc_status rc_cmd_merge(int argc, char **argv) {
  merge_args *a = calloc(1, sizeof *a);
  if (!a) return RC_ERR_OUT_OF_MEMORY;
  rc_status st = rc_parse_command(&rc_merge_spec, argc, argv, a);
  if (st != RC_OK) {
    free(a);
    return st == RC_DONE ? RC_OK : st;
  }
  size_t n = 0;
  while (n < MAX_PARTS && a->parts[n]) n++;
  part *parts = calloc(n, sizeof *parts);
  rc_file_role *roles = calloc(n + 1, sizeof *roles);
  if (!parts || !roles) st = RC_ERR_OUT_OF_MEMORY;
  if (st == RC_OK && strcmp(a->output, "-") == 0) {
    rc_usage_error(&rc_merge_spec, "-o -: images are not written to standard output; name a file");
    st = RC_ERR_USAGE;
  }
  if (st == RC_OK && rc_check_output(a->output, "the image") != RC_OK) st = RC_ERR_IO;
  for (size_t i = 0; st == RC_OK && i < n; i++) {
    parts[i].path = a->parts[i];
    roles[i] = (rc_file_role){a->parts[i], "a part", false};
  }
  roles[n] = (rc_file_role){a->output, "the image", true};
  if (st == RC_OK) st = rc_check_distinct(roles, n + 1);
  if (st == RC_OK) st = rc_output_check_format(a->output);
  /* Every header first; the readers are closed until the pixels are needed, so that a
   * frame of thousands of parts never holds thousands of files open. */
  for (size_t i = 0; st == RC_OK && i < n; i++) {
    st = open_part(&parts[i]);
    rc_image_reader_close(parts[i].reader);
    parts[i].reader = NULL;
  }
  if (st == RC_OK) st = check_agreement(parts, n);
  if (st == RC_OK) st = check_coverage(parts, n);
  rc_output *out = NULL;
  if (st == RC_OK) {
    /* The merged image says what a single render of the frame says. */
    rc_part_info whole = parts[0].info;
    whole.region = (rc_region){0, 0, whole.width, whole.height};
    whole.shard_index = whole.shard_count = 0;
    rc_image_meta meta[RC_PART_FIELDS];
    char text[RC_PART_FIELDS][64], quantize[16];
    int m = rc_part_meta(&whole, meta, text);
    rc_encoding encoding;
    if (!rc_part_encoding(whole.settings, &encoding)) {
      rc_error("%s: its header's encoding settings are not ones render writes (\"%s\")", parts[0].path, whole.settings);
      st = RC_ERR_INPUT;
    }
    rc_part_setting(whole.settings, "quantize", quantize, sizeof quantize);
    rc_output_install_signal_handlers();
    const bool aov = parts[0].channels != 3;
    if (st == RC_OK && aov && !rc_has_extension(a->output, ".exr")) {
      rc_error("%s: the parts are AOV files, whose decision channels need a multi-channel float file: name it .exr",
               a->output);
      st = RC_ERR_USAGE;
    }
    if (st == RC_OK)
      st = rc_output_open(aov ? NULL : a->output, aov ? a->output : NULL, whole.width, whole.height,
                          encoding,
                          strcmp(quantize, "truncate") == 0, meta, m, &out);
  }
  if (st == RC_OK) st = write_merged(parts, n, out);
  rc_status cst = rc_output_close(out, st == RC_OK);
  if (st == RC_OK) st = cst;
  if (st == RC_OK && !a->quiet)
    fprintf(stderr, "vkraycast: merged %zu %spart%s into %s (%u x %u)\n", n, parts[0].channels == 3 ? "" : "AOV ",
            n == 1 ? "" : "s", a->output, parts[0].info.width, parts[0].info.height);
  if (parts) close_parts(parts, n);
  free(parts);
  free(roles);
  free(a);
  return st;
}
