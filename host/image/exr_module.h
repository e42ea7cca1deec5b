/* exr_module.h: the two halves of vkraycast-exr.so's table (image_module.h): the readers
 * (exr_read.cpp) and the writers (exr_write.cpp), and what both use. Private to the module
 * (C++). */
#ifndef RC_EXR_MODULE_H
#define RC_EXR_MODULE_H

#include "image/image_module.h"

#include <cstdio>
#include <string>

/* The reason, into the caller's buffer where it gave one (err may be NULL). */
inline void set_error(char *err, size_t len, const std::string &what) {
  if (err && len) std::snprintf(err, len, "%s", what.c_str());
}

/* Fills the writers' entries of the module's table. */
void rc_exr_writers(rc_image_api *table);
/* Starts OpenEXR's global thread pool, once, with a thread for each CPU this process may
 * run on: zip compression works on blocks of 16 rows in parallel, as it did through
 * OpenImageIO (which sets the same pool to the machine's threads). */
void rc_exr_threads(void);

#endif
