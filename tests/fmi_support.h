/* What the FMI hosts of the suite (fmi_master.c, fmu_host.c) share: a logger that prints
 * the FMU's messages to stderr as "[instance category status N] message", and the file URI
 * of a folder, percent-encoded as RFC 3986 asks (a folder's name may hold a space). */
#ifndef TIREFE_FMI_SUPPORT_H
#define TIREFE_FMI_SUPPORT_H

#include <ctype.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu/fmi2.h"

static void fmi_logger(fmi2ComponentEnvironment environment, fmi2String instance, fmi2Status status,
                       fmi2String category, fmi2String message, ...) {
  (void)environment;
  va_list arguments;
  va_start(arguments, message);
  fprintf(stderr, "[%s %s status %d] ", instance, category, (int)status);
  vfprintf(stderr, message, arguments);
  fputc('\n', stderr);
  va_end(arguments);
}

/* "file://" and the folder's absolute path, percent-encoded; 0 if there is no such folder. */
static int folder_uri(const char* folder, char* uri, size_t size) {
  char absolute[PATH_MAX];
  if (!realpath(folder, absolute)) return 0;
  size_t n = (size_t)snprintf(uri, size, "file://");
  for (const char* c = absolute; *c && n + 4 < size; ++c) {
    if (isalnum((unsigned char)*c) || strchr("/-._~", *c))
      uri[n++] = *c;
    else
      n += (size_t)snprintf(uri + n, size - n, "%%%02X", (unsigned char)*c);
  }
  uri[n] = '\0';
  return 1;
}

#endif /* TIREFE_FMI_SUPPORT_H */
