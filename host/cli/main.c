/* vkraycast: a ray caster whose renderer is a Vulkan compute shader.
 *   vkraycast render SCENE -o OUT [options]   render a scene to an image (cmd_render.c)
 *   vkraycast merge PARTS... -o OUT           join the parts of a frame (cmd_merge.c)
 *   vkraycast compare A B [options]           metrics between two images (cmd_compare.c)
 *   vkraycast tradeoff SCENE... --out DIR     speed against accuracy on the user's scenes (cmd_tradeoff.c)
 *   vkraycast prepare SCENE -o FILE.vkrs      pack a scene and build its BVH once (cmd_prepare.c)
 *   vkraycast devices                         list the Vulkan devices (cmd_devices.c)
 * Exit status: 0 ok, 1 images differ (compare), 2 bad input or usage, 3 device failure.
 * The command-line conventions are in docs/cli.md. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan.h>

#include "cli/cli.h"
#include "cli/huge_pages.h"
#include "cli/options.h"
#include "cli/output.h"
#include "cli/safe_streams.h"
#include "vkraycast_build.h"
#include "vkraycast_revision.h"

static const char usage[] =
    "usage: vkraycast <command> [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE -o OUT   render a scene file (or - : standard input) to an image (PNG, EXR, ...)\n"
    "  merge PARTS... -o OUT join the parts of one frame (render --shard/--region, .exr) into one\n"
    "                        image, bit for bit the single render's\n"
    "  compare A B           compare two images (or AOV files): error metrics, heat map, exit 1 if beyond\n"
    "                        thresholds\n"
    "  tradeoff SCENE... --out DIR\n"
    "                        measure what accuracy costs on your scenes: variants x spp, timed and\n"
    "                        compared with the CPU f64 reference; a CSV and a plot\n"
    "  prepare SCENE -o FILE.vkrs\n"
    "                        pack the scene and build its BVH once, for renders (a farm's shards)\n"
    "                        that map FILE.vkrs instead of parsing: the same image, bit for bit\n"
    "  devices               list Vulkan devices\n"
    "\n"
    "  vkraycast <command> --help   options of a command\n"
    "  vkraycast --version\n";

static const struct {
  const char *name;
  rc_status (*run)(int argc, char **argv);
  const rc_command_spec *spec;
} commands[] = {
    {"render", rc_cmd_render, &rc_render_spec},
    {"merge", rc_cmd_merge, &rc_merge_spec},
    {"compare", rc_cmd_compare, &rc_compare_spec},
    {"tradeoff", rc_cmd_tradeoff, &rc_tradeoff_spec},
    {"prepare", rc_cmd_prepare, &rc_prepare_spec},
    {"devices", rc_cmd_devices, &rc_devices_spec},
};
#define COMMAND_COUNT (sizeof commands / sizeof *commands)

const char *rc_version_string(void) {
  static char text[96];
  if (!text[0])
    snprintf(text, sizeof text, "%s%s%s%s", VKRAYCAST_VERSION, VKRAYCAST_GIT_REVISION[0] ? " (git " : "",
             VKRAYCAST_GIT_REVISION, VKRAYCAST_GIT_REVISION[0] ? ")" : "");
  return text;
}

static void print_version(void) {
  uint32_t loader = VK_API_VERSION_1_0;
  /* vkEnumerateInstanceVersion is a 1.1 loader entry point; a 1.0 loader lacks it. */
  PFN_vkEnumerateInstanceVersion enumerate =
      (PFN_vkEnumerateInstanceVersion)vkGetInstanceProcAddr(NULL, "vkEnumerateInstanceVersion");
  if (enumerate) enumerate(&loader);
  printf("vkraycast %s\n", rc_version_string());
  printf("built with: Vulkan headers %s, loader %s; shader compiler %s\n", VKRAYCAST_VULKAN_HEADERS,
         VKRAYCAST_VULKAN_LIBRARY, VKRAYCAST_GLSLANG);
  printf("running with: Vulkan loader %u.%u.%u\n", VK_API_VERSION_MAJOR(loader), VK_API_VERSION_MINOR(loader),
         VK_API_VERSION_PATCH(loader));
}

/* The subcommand may follow options (`vkraycast --quiet render scene.json -o x.png`):
 * it is the first argument that is neither an option nor the value of one. An option
 * that takes a value in any command is taken to take one here; `--opt=value` never
 * swallows the next argument. Returns the index, or -1. */
static int find_command(int argc, char **argv) {
  const rc_command_spec *specs[COMMAND_COUNT];
  for (size_t i = 0; i < COMMAND_COUNT; i++) specs[i] = commands[i].spec;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--") == 0) return -1;
    if (a[0] != '-' || a[1] == '\0') return i;
    if (rc_option_takes_value(specs, COMMAND_COUNT, a)) i++;
  }
  return -1;
}

int main(int argc, char **argv) {
  rc_huge_pages_reexec(argv);
  rc_safe_streams_install();
  /* Before any thread starts, so that every one inherits the blocked signals and only
   * the signal thread takes them (cli/output.h). */
  rc_output_install_signal_handlers();
  if (argc < 2) {
    fputs(usage, stderr);
    return rc_status_exit_code(RC_ERR_USAGE);
  }
  if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0)) {
    fputs(usage, stdout);
    return 0;
  }
  if (argc == 2 && (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0)) {
    print_version();
    return 0;
  }
  int at = find_command(argc, argv);
  if (at < 0) {
    rc_error("no command given (render, merge, compare, tradeoff or devices)");
    fputs(usage, stderr);
    return rc_status_exit_code(RC_ERR_USAGE);
  }
  size_t k = 0;
  while (k < COMMAND_COUNT && strcmp(argv[at], commands[k].name) != 0) k++;
  if (k == COMMAND_COUNT) {
    const char *names[COMMAND_COUNT];
    for (size_t i = 0; i < COMMAND_COUNT; i++) names[i] = commands[i].name;
    const char *near = rc_nearest(argv[at], names, COMMAND_COUNT);
    if (near)
      rc_error("unknown command '%s' (did you mean %s?)", argv[at], near);
    else
      rc_error("unknown command '%s'", argv[at]);
    fputs(usage, stderr);
    return rc_status_exit_code(RC_ERR_USAGE);
  }
  /* The command's arguments: the options written before it, then everything after it. */
  char **args = malloc(sizeof *args * (size_t)argc);
  if (!args) return rc_status_exit_code(RC_ERR_OUT_OF_MEMORY);
  int n = 0;
  for (int i = 1; i < argc; i++)
    if (i != at) args[n++] = argv[i];
  rc_status st = commands[k].run(n, args);
  free(args);
  return rc_status_exit_code(st);
}
