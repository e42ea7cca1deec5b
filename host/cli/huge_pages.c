/* huge_pages.c: see huge_pages.h. */
#define _GNU_SOURCE
#include "cli/huge_pages.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define TUNABLE "glibc.malloc.hugetlb"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RC_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define RC_SANITIZED 1
#endif

#ifndef RC_SANITIZED
/* "always [madvise] never": hugetlb=1 advises malloc's memory with MADV_HUGEPAGE, which
 * the kernel honours in both the always and the madvise modes. */
static int thp_available(void) {
  FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  if (!f) return 0;
  char mode[128] = "";
  int ok = fgets(mode, sizeof mode, f) != NULL;
  fclose(f);
  return ok && !strstr(mode, "[never]");
}
#endif

void rc_huge_pages_reexec(char **argv) {
#ifdef RC_SANITIZED
  (void)argv;
#else
  const char *off = getenv("VKRAYCAST_HUGE_PAGES");
  if (off && strcmp(off, "0") == 0) return;
  const char *old = getenv("GLIBC_TUNABLES");
  if (old && strstr(old, TUNABLE)) return;
  if (!thp_available()) return;
  /* Tunables are colon-separated; the user's own ones are kept. */
  size_t len = (old ? strlen(old) + 1 : 0) + sizeof TUNABLE "=1";
  char *value = malloc(len);
  if (!value) return;
  snprintf(value, len, "%s%s" TUNABLE "=1", old ? old : "", old && *old ? ":" : "");
  char *saved = old ? strdup(old) : NULL;
  if ((!old || saved) && setenv("GLIBC_TUNABLES", value, 1) == 0) {
    execv("/proc/self/exe", argv);
    /* Not executed (no /proc, the binary replaced on disk): run as started. */
    if (saved)
      setenv("GLIBC_TUNABLES", saved, 1);
    else
      unsetenv("GLIBC_TUNABLES");
  }
  free(saved);
  free(value);
#endif
}
