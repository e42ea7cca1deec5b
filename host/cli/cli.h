/* cli.h: the subcommands. Each takes the arguments after its name (with any options
 * written before the name) and returns a status that main() turns into the exit code;
 * its option table (cli/options.h) is exported for main() and the tests. */
#ifndef RC_CLI_H
#define RC_CLI_H

#include "cli/options.h"
#include "base/rc_base.h"

rc_status rc_cmd_render(int argc, char **argv);
rc_status rc_cmd_devices(int argc, char **argv);
rc_status rc_cmd_compare(int argc, char **argv);
rc_status rc_cmd_merge(int argc, char **argv);
rc_status rc_cmd_tradeoff(int argc, char **argv);
rc_status rc_cmd_prepare(int argc, char **argv);

extern const rc_command_spec rc_render_spec, rc_compare_spec, rc_devices_spec, rc_merge_spec, rc_tradeoff_spec,
    rc_prepare_spec;

/* "0.1.0 (git abc123...)": the version, with the git revision when built from a checkout
 * (main.c; --version and the statistics). */
const char *rc_version_string(void);

#endif
