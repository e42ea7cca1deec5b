/* cli.h: the subcommands. Each takes the arguments after its name and returns a status
 * that main() turns into the exit code. */
#ifndef RC_CLI_H
#define RC_CLI_H

#include "rc_base.h"

rc_status rc_cmd_render(int argc, char **argv);
rc_status rc_cmd_devices(int argc, char **argv);
rc_status rc_cmd_compare(int argc, char **argv);

/* Parses a whole decimal number in [lo, hi] for option `name`; prints the error. */
rc_status rc_cli_uint(const char *name, const char *text, uint32_t lo, uint32_t hi, uint32_t *out);

#endif
