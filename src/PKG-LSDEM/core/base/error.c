/* error.c -- status names and the error-message buffer. */
#include "lsdem_base.h"

#include <stdarg.h>
#include <stdio.h>

const char *lsdem_status_name(lsdem_status s)
{
  switch (s) {
  case LSDEM_OK: return "ok";
  case LSDEM_ERR_ARG: return "invalid argument";
  case LSDEM_ERR_IO: return "i/o error";
  case LSDEM_ERR_FORMAT: return "format error";
  case LSDEM_ERR_NOMEM: return "out of memory";
  case LSDEM_ERR_NUMERIC: return "numerical error";
  }
  return "unknown error";
}

lsdem_status lsdem_fail(lsdem_error *err, lsdem_status s, const char *fmt, ...)
{
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
  }
  return s;
}
