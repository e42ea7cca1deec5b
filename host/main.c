/* vkraycast: a ray caster whose renderer is a Vulkan compute shader.
 *   vkraycast render SCENE -o OUT [options]   render a scene to an image (cmd_render.c)
 *   vkraycast compare A B [options]           metrics between two images (cmd_compare.c)
 *   vkraycast devices                         list the Vulkan devices (cmd_devices.c)
 * Exit status: 0 ok, 1 images differ (compare), 2 bad input or usage, 3 device failure. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

#ifndef VKRAYCAST_VERSION
#define VKRAYCAST_VERSION "0.0.0"
#endif

static const char usage[] =
    "usage: vkraycast <command> [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE -o OUT   render a scene file to an image (PNG, EXR, ...)\n"
    "  compare A B           compare two images (or AOV files): error metrics, heat map, exit 1 if beyond\n"
    "                        thresholds\n"
    "  devices               list Vulkan devices\n"
    "\n"
    "  vkraycast <command> --help   options of a command\n"
    "  vkraycast --version\n";

int main(int argc, char **argv) {
  if (argc < 2) {
    fputs(usage, stderr);
    return rc_status_exit_code(RC_ERR_USAGE);
  }
  const char *cmd = argv[1];
  rc_status st;
  if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
    fputs(usage, stdout);
    st = RC_OK;
  } else if (strcmp(cmd, "--version") == 0) {
    printf("vkraycast %s\n", VKRAYCAST_VERSION);
    st = RC_OK;
  } else if (strcmp(cmd, "render") == 0) {
    st = rc_cmd_render(argc - 2, argv + 2);
  } else if (strcmp(cmd, "compare") == 0) {
    st = rc_cmd_compare(argc - 2, argv + 2);
  } else if (strcmp(cmd, "devices") == 0) {
    st = rc_cmd_devices(argc - 2, argv + 2);
  } else {
    rc_error("unknown command '%s'", cmd);
    fputs(usage, stderr);
    st = RC_ERR_USAGE;
  }
  return rc_status_exit_code(st);
}
