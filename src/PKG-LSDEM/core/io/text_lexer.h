/* text_lexer.h -- whitespace-separated tokens of a NUL-terminated text, with line numbers,
 * for the core's text readers (STL and OBJ meshes: io/mesh_read.c; ESRI ASCII grids:
 * io/heightmap.c). Private to the core. */
#ifndef LSDEM_IO_TEXT_LEXER_H
#define LSDEM_IO_TEXT_LEXER_H

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  const char *p; /* the next character */
  long line;     /* its line (1-based when started at 1) */
} text_lexer;

/* The next token on the current line; 0 at its end (the lexer stays before the newline). */
static inline int lexer_next_on_line(text_lexer *lx, const char **tok, size_t *len)
{
  while (*lx->p == ' ' || *lx->p == '\t' || *lx->p == '\r' || *lx->p == '\v' || *lx->p == '\f')
    lx->p++;
  if (*lx->p == '\0' || *lx->p == '\n') return 0;
  *tok = lx->p;
  while (*lx->p && !isspace((unsigned char)*lx->p)) lx->p++;
  *len = (size_t)(lx->p - *tok);
  return 1;
}

/* The next token anywhere, counting the lines passed; 0 at the end of the text. */
static inline int lexer_next(text_lexer *lx, const char **tok, size_t *len)
{
  while (*lx->p && isspace((unsigned char)*lx->p)) lx->line += *lx->p++ == '\n';
  return lexer_next_on_line(lx, tok, len);
}

static inline int token_is(const char *tok, size_t len, const char *word)
{
  return len == strlen(word) && strncmp(tok, word, len) == 0;
}

/* The whole token as a number (strtod: "nan" and "inf" included); 0 if it is not one. */
static inline int token_double(const char *tok, size_t len, double *v)
{
  char buf[64];
  if (len == 0 || len >= sizeof buf) return 0;
  memcpy(buf, tok, len);
  buf[len] = '\0';
  char *end;
  *v = strtod(buf, &end);
  return *end == '\0';
}

/* The whole token as a finite number; 0 if it is not one. */
static inline int token_number(const char *tok, size_t len, double *v)
{
  return token_double(tok, len, v) && isfinite(*v);
}

#endif /* LSDEM_IO_TEXT_LEXER_H */
