/* safe_streams.h: standard output and standard error that cannot carry a terminal
 * control sequence. Messages quote what the user typed and what files hold (names, keys,
 * paths, channel names); an ESC in a material name would recolour the terminal, a
 * carriage return overwrite the line before. Every byte written to either stream goes
 * through a filter that spells C0 control characters other than newline and tab, and
 * DEL, as \xNN: one place, so no message can forget (docs/cli.md, "Messages"). The
 * progress line's own carriage return is written past the filter (rc_progress). */
#ifndef RC_CLI_SAFE_STREAMS_H
#define RC_CLI_SAFE_STREAMS_H

#include <stdio.h>

/* Replaces stdout and stderr by filtering streams on the same descriptors (stderr stays
 * unbuffered). Once, at the start of main. */
void rc_safe_streams_install(void);

#endif
