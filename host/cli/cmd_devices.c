/* cmd_devices.c: `vkraycast devices`: the Vulkan devices, for render --device. */
#include "cli/cli.h"
#include "gpu/vk_context.h"

typedef struct {
  const char *none[1];
} devices_args;

const rc_command_spec rc_devices_spec = {
    .name = "devices",
    .synopsis = "",
    .summary = "Lists the Vulkan devices: index (for render --device), name, type, driver,\n"
               "API version, and whether shaderFloat64 is supported.",
    .positional_offset = 0,
};

rc_status rc_cmd_devices(int argc, char **argv) {
  devices_args a = {0};
  rc_status st = rc_parse_command(&rc_devices_spec, argc, argv, &a);
  if (st != RC_OK) return st == RC_DONE ? RC_OK : st;
  return rc_vk_list_devices();
}
