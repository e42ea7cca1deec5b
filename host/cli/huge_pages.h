/* huge_pages.h: glibc's malloc on transparent huge pages, for the whole process.
 * Starting a render is mostly loading shared libraries: OpenImageIO's ~260 (image_module.h)
 * and lavapipe's LLVM. Their constructors and the driver's shader compiler allocate many
 * MiB, and on a VM each first touch of a 4 KiB page is a costly fault (docs/performance.md,
 * finding 7: ~3 ms per MiB). glibc reads its tunables once, before main, so the one way to
 * set glibc.malloc.hugetlb=1 for a process is to start it with GLIBC_TUNABLES naming it:
 * rc_huge_pages_reexec() re-executes the program once with the tunable appended
 * (docs/performance.md, finding 8, measures what that saves). */
#ifndef RC_CLI_HUGE_PAGES_H
#define RC_CLI_HUGE_PAGES_H

/* Returns only when it does not re-execute: GLIBC_TUNABLES already names the tunable (the
 * user's choice, or this is the re-executed process), VKRAYCAST_HUGE_PAGES=0, the kernel
 * has transparent huge pages off, the build is sanitized (ASan brings its own allocator),
 * or the exec failed (then nothing has changed). Call first thing in main. */
void rc_huge_pages_reexec(char **argv);

#endif
