#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "vk/vk_context.h"

rc_status rc_cmd_devices(int argc, char **argv) {
  if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) {
    puts("usage: vkraycast devices\n\nLists the Vulkan devices: index (for render --device), name, type, driver,\n"
         "API version, and whether shaderFloat64 is supported.");
    return RC_OK;
  }
  if (argc > 0) {
    rc_error("devices: unexpected argument '%s'", argv[0]);
    return RC_ERR_USAGE;
  }
  return rc_vk_list_devices();
}
